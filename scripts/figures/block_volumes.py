#!/usr/bin/python3
"""Block-volume histogram with the Weibull fit (Figure 7 of the paper).

Usage: /usr/bin/python3 scripts/figures/block_volumes.py blocks.csv [--summary summary.json]
       -o block_volumes.png [--materials rock1,rock2]

Left: histogram of the block volumes (density, linear axes, up to the 99th percentile so
that a few huge blocks do not squash it) with the Weibull density of the fit in
summary.json (`weibull.shape` k, `weibull.scale` lambda: f(v) = k/lambda (v/lambda)^(k-1)
exp(-(v/lambda)^k)). Right: the same volumes as an exceedance curve on log axes, with the
fit's exp(-(v/lambda)^k). The figure draws the fit rockmass computed; it fits nothing.
With --materials only the blocks of those materials are drawn (the fit stays the
summary's). The title gives min / mean / max of the drawn volumes.
"""
import argparse
import sys

import numpy as np

from figure_io import number, plt, read_rows, read_summary, save


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv", help="blocks.csv")
    parser.add_argument("--summary", help="summary.json with weibull.{shape,scale}")
    parser.add_argument("--materials", default="", help="comma-separated material names")
    parser.add_argument("-o", "--output", default="block_volumes.png")
    args = parser.parse_args(argv)

    rows = read_rows(args.csv, ["id", "volume", "material"])
    wanted = {m for m in args.materials.split(",") if m}
    v = np.array([number(r, "volume", args.csv, i) for i, r in enumerate(rows, start=2)
                  if not wanted or r["material"] in wanted])
    v = v[v > 0]
    if len(v) == 0:
        sys.exit(f"{args.csv}: no block volumes to draw")
    fit = (read_summary(args.summary).get("weibull") if args.summary else None) or None

    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.5))
    top = np.percentile(v, 99) if len(v) > 20 else v.max()
    bins = np.linspace(0, top, 40)
    left.hist(v[v <= top], bins=bins, density=True, color="#9ab", edgecolor="#567",
              label=f"{len(v)} blocks")
    xs = np.linspace(max(top * 1e-3, 1e-12), top, 400)
    label_fit = None
    if fit:
        k, lam = float(fit["shape"]), float(fit["scale"])
        # The histogram shows v <= top only; scale the pdf to the same share of blocks.
        share = np.mean(v <= top)
        pdf = (k / lam) * (xs / lam) ** (k - 1) * np.exp(-(xs / lam) ** k) / share
        label_fit = f"Weibull k = {k:.3g}, lambda = {lam:.3g} m3"
        left.plot(xs, pdf, "r-", lw=1.5, label=label_fit)
        left.set_ylim(0, 1.5 * max(np.histogram(v[v <= top], bins=bins, density=True)[0]))
    left.set_xlabel("block volume (m3)")
    left.set_ylabel("probability density (1/m3)")
    left.legend(fontsize=8)
    left.grid(alpha=0.3)

    s = np.sort(v)
    exceed = 1.0 - np.arange(len(s)) / len(s)
    right.loglog(s, exceed, ".", ms=2, color="#345", label="blocks")
    if fit:
        grid = np.logspace(np.log10(s[0]), np.log10(s[-1]), 200)
        right.loglog(grid, np.exp(-(grid / lam) ** k), "r-", lw=1.5, label=label_fit)
    right.set_xlabel("block volume v (m3)")
    right.set_ylabel("fraction of blocks larger than v")
    right.legend(fontsize=8)
    right.grid(alpha=0.3, which="both")
    fig.suptitle(f"Block volumes: min {v.min():.3g}, mean {v.mean():.3g}, max {v.max():.4g} m3")
    fig.tight_layout()
    save(fig, args.output)
    print(f"block_volumes: wrote {args.output}")


if __name__ == "__main__":
    main()
