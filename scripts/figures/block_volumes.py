#!/usr/bin/python3
"""Block-volume distribution of the rock with its Weibull fit (Figure 7 of the paper).

Usage: /usr/bin/python3 scripts/figures/block_volumes.py blocks.csv [--summary summary.json]
       -o block_volumes.png [--materials rock1,rock2]

The population is the rock mass's blocks: blocks.csv rows whose `structure` is empty (the
dam and other structures are not rock; files without the column are taken whole), and with
--materials only those materials. The fit drawn is the one rockmass computed for that same
population, summary.json's `rock.weibull` (shape k, scale lambda; the whole model's
`weibull` when there is no rock entry); the figure fits nothing. With --materials no fit is
drawn (no summary fit is of that subset).

Left: histogram of log10(v) with bins of equal width in log10 (the volumes span many
decades), as a density per decade, with the fit's density per decade
f(v) v ln 10, f(v) = k/lambda (v/lambda)^(k-1) exp(-(v/lambda)^k). Right: the fraction of
blocks larger than v on log axes, with the fit's exp(-(v/lambda)^k), drawn down to half of
1/N (below that no block could show it).
"""
import argparse
import math
import sys

import numpy as np

from figure_io import add_scene_argument, number, plt, read_rows, read_summary, save


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv", help="blocks.csv")
    parser.add_argument("--summary", help="summary.json with rock.weibull.{shape,scale}")
    parser.add_argument("--materials", default="", help="comma-separated material names")
    parser.add_argument("-o", "--output", default="block_volumes.png")
    add_scene_argument(parser)
    args = parser.parse_args(argv)

    rows = read_rows(args.csv, ["id", "volume", "material"])
    wanted = {m for m in args.materials.split(",") if m}
    structures = sum(1 for r in rows if r.get("structure"))
    v = np.array([number(r, "volume", args.csv, i) for i, r in enumerate(rows, start=2)
                  if not r.get("structure") and (not wanted or r["material"] in wanted)])
    v = v[v > 0]
    if len(v) == 0:
        sys.exit(f"{args.csv}: no rock block volumes to draw")
    summary = read_summary(args.summary) if args.summary else {}
    rock = summary.get("rock") if isinstance(summary.get("rock"), dict) else None
    fit = None if wanted else ((rock or {}).get("weibull") if rock else summary.get("weibull"))
    population = "rock blocks" + (f" of {', '.join(sorted(wanted))}" if wanted else "")

    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.5))
    logs = np.log10(v)
    low, high = math.floor(logs.min()), math.ceil(logs.max())
    if high <= low:
        high = low + 1
    per_decade = 4
    edges = np.linspace(low, high, (high - low) * per_decade + 1)
    counts, _ = np.histogram(logs, bins=edges)
    density = counts / (len(v) * (edges[1] - edges[0]))
    left.bar(edges[:-1], density, width=np.diff(edges), align="edge", color="#9ab",
             edgecolor="#567", label=f"{len(v)} {population}")
    label_fit = None
    if fit:
        k, lam = float(fit["shape"]), float(fit["scale"])
        xs = np.linspace(low, high, 400)
        vs = 10.0 ** xs
        pdf = (k / lam) * (vs / lam) ** (k - 1) * np.exp(-(vs / lam) ** k) * vs * math.log(10)
        label_fit = f"Weibull fit of the rock: k = {k:.3g}, λ = {lam:.3g} m³"
        left.plot(xs, pdf, "r-", lw=1.5, label=label_fit)
    left.set_xlabel("block volume v (m³), log scale")
    ticks = np.arange(low, high + 1, 1 if high - low <= 8 else 2)
    left.set_xticks(ticks)
    left.set_xticklabels([f"$10^{{{int(t)}}}$" for t in ticks])
    left.set_ylabel("share of blocks per decade of volume")
    left.legend(fontsize=8)
    left.grid(alpha=0.3)

    s = np.sort(v)
    exceed = 1.0 - np.arange(len(s)) / len(s)
    right.loglog(s, exceed, ".", ms=2, color="#345", label=f"{len(v)} {population}")
    floor = 0.5 / len(s)
    if fit:
        grid = np.logspace(np.log10(s[0]), np.log10(s[-1]), 200)
        tail = np.exp(-(grid / lam) ** k)
        keep = tail >= floor
        right.loglog(grid[keep], tail[keep], "r-", lw=1.5, label=label_fit)
    right.set_ylim(floor, 1.5)
    right.set_xlabel("block volume v (m³)")
    right.set_ylabel("fraction of blocks larger than v")
    right.legend(fontsize=8)
    right.grid(alpha=0.3, which="both")
    excluded = (f"; {structures} block{'s' if structures != 1 else ''} of structures not "
                "included" if structures else "")
    fig.suptitle(f"Rock block volumes: {len(v)} blocks, min {v.min():.3g}, median "
                 f"{np.median(v):.3g}, max {v.max():.4g} m³{excluded}", fontsize=10)
    fig.tight_layout()
    save(fig, args.output, facts={
        "population": population, "blocks": int(len(v)), "structure_blocks": structures,
        "fit": "rock.weibull" if fit and rock else ("weibull" if fit else None),
        "bins": "log10", "units": "m3"}, scene=args.scene)
    print(f"block_volumes: wrote {args.output}")


if __name__ == "__main__":
    main()
