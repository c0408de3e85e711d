#!/usr/bin/python3
"""Overload curve: monitor displacement against the overload factor K (Figure 10).

Usage: /usr/bin/python3 scripts/figures/overload_curve.py overload.csv
       [--summary summary.json] -o overload_curve.png

overload.csv (factor,monitor,ux,uy,uz,u[,at_rest,steps]): horizontal (ux) and vertical (uz)
displacement of every monitor against K, both panels in one unit, cm, mm or um (whichever
suits the largest value of either). Each point shows how its run ended: a filled circle at
rest, an open circle not at rest within the step limit, a cross stopped early as failing
(summary.json's runs[].failing, or the at_rest column), a dot when neither says. Only runs
at rest are joined into a curve: the displacement of a run that did not come to rest is
where it stopped, not a point of the load-displacement curve. When summary.json has the
overload's bracket [last_stable, first_unstable] it is shaded, and a finite K_s is marked
with a vertical line labelled with the bracket's half-width (K_s is its midpoint).
"""
import argparse
import math

import numpy as np

from figure_io import (add_scene_argument, number, plt, read_rows, read_summary, save,
                       unit_for)

def outcomes(summary):
    """{factor: 'rest' | 'moving' | 'failing'} from summary.json's overload runs."""
    runs = (summary.get("overload") or {}).get("runs") or []
    result = {}
    for run in runs:
        if not isinstance(run, dict) or "factor" not in run:
            continue
        if run.get("at_rest"):
            result[run["factor"]] = "rest"
        elif run.get("failing"):
            result[run["factor"]] = "failing"
        else:
            result[run["factor"]] = "moving"
    return result


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv", help="overload.csv")
    parser.add_argument("--summary", help="summary.json (safety_factor, overload runs)")
    parser.add_argument("-o", "--output", default="overload_curve.png")
    add_scene_argument(parser)
    args = parser.parse_args(argv)

    rows = read_rows(args.csv, ["factor", "monitor", "ux", "uy", "uz", "u"])
    summary = read_summary(args.summary) if args.summary else {}
    ended = outcomes(summary)
    series = {}
    for line, row in enumerate(rows, start=2):
        factor = number(row, "factor", args.csv, line)
        if factor not in ended and row.get("at_rest") in ("0", "1"):
            ended[factor] = "rest" if row["at_rest"] == "1" else "moving"
        series.setdefault(row["monitor"], []).append(
            [factor] + [number(row, k, args.csv, line) for k in ("ux", "uz")])
    ks = summary.get("safety_factor")
    overload = summary.get("overload") or {}
    low, high = overload.get("last_stable"), overload.get("first_unstable")
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5), sharex=True)
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    scale, unit = unit_for(v[c] for points in series.values() for v in points for c in (1, 2))
    for ax, column, name in ((axes[0], 1, "horizontal displacement ux"),
                             (axes[1], 2, "vertical displacement uz")):
        for i, monitor in enumerate(series):
            colour = colours[i % len(colours)]
            data = np.array(sorted(series[monitor]))
            rest = np.array([ended.get(f) == "rest" for f in data[:, 0]])
            if rest.any():
                ax.plot(data[rest, 0], scale * data[rest, column], "-", color=colour, lw=1,
                        label=monitor)
            else:
                ax.plot([], [], "-", color=colour, lw=1, label=monitor)
            for factor, value in zip(data[:, 0], scale * data[:, column]):
                how = ended.get(factor)
                if how == "failing":
                    ax.plot(factor, value, "x", color=colour, ms=6)
                elif how is None:  # no summary and no at_rest column: outcome unknown
                    ax.plot(factor, value, ".", color=colour, ms=5)
                else:
                    ax.plot(factor, value, "o", ms=5, color=colour,
                            mfc=colour if how == "rest" else "white")
        if all(isinstance(v, (int, float)) for v in (low, high)):
            ax.axvspan(low, high, color="r", alpha=0.08, label=f"bracket [{low:g}, {high:g}]")
        if isinstance(ks, (int, float)) and math.isfinite(ks):
            if all(isinstance(v, (int, float)) for v in (low, high)):
                label = f"K_s = {ks:g} ± {(high - low) / 2:g}"
            else:
                label = f"K_s = {ks:g}"
            ax.axvline(ks, color="r", ls="--", lw=1, label=label)
        ax.set_xlabel("overload factor K")
        ax.set_ylabel(f"{name} ({unit})")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle(("Overload: monitor displacement at the end of each run against K\n"
                  "● at rest (joined)   ○ not at rest within the step limit   "
                  "× stopped early, failing"), fontsize=10)
    fig.tight_layout()
    save(fig, args.output, facts={
        "unit": unit, "joined": "runs at rest only",
        "bracket": [low, high] if all(isinstance(v, (int, float)) for v in (low, high)) else None,
        "K_s": ks if isinstance(ks, (int, float)) and math.isfinite(ks) else None},
         scene=args.scene or summary.get("name", ""))
    print(f"overload_curve: wrote {args.output}")


if __name__ == "__main__":
    main()
