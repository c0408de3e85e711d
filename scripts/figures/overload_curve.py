#!/usr/bin/python3
"""Overload curve: monitor displacement against the overload factor K (Figure 10).

Usage: /usr/bin/python3 scripts/figures/overload_curve.py overload.csv
       [--summary summary.json] -o overload_curve.png

overload.csv (factor,monitor,ux,uy,uz,u): horizontal (ux) and vertical (uz) displacement
of every monitor, in cm, against K. When summary.json has a finite `safety_factor`, it is
marked with a vertical line.
"""
import argparse
import math

import numpy as np

from figure_io import number, plt, read_rows, read_summary, save


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv", help="overload.csv")
    parser.add_argument("--summary", help="summary.json (safety_factor)")
    parser.add_argument("-o", "--output", default="overload_curve.png")
    args = parser.parse_args(argv)

    rows = read_rows(args.csv, ["factor", "monitor", "ux", "uy", "uz", "u"])
    series = {}
    for line, row in enumerate(rows, start=2):
        series.setdefault(row["monitor"], []).append(
            [number(row, k, args.csv, line) for k in ("factor", "ux", "uz")])
    ks = read_summary(args.summary).get("safety_factor") if args.summary else None
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5), sharex=True)
    for ax, column, label in ((axes[0], 1, "horizontal displacement ux (cm)"),
                              (axes[1], 2, "vertical displacement uz (cm)")):
        for monitor in series:
            data = np.array(sorted(series[monitor]))
            ax.plot(data[:, 0], 100.0 * data[:, column], "o-", ms=3, label=monitor)
        if isinstance(ks, (int, float)) and math.isfinite(ks):
            ax.axvline(ks, color="r", ls="--", lw=1, label=f"K_s = {ks:g}")
        ax.set_xlabel("overload factor K")
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle("Overload: monitor displacement against K")
    fig.tight_layout()
    save(fig, args.output)
    print(f"overload_curve: wrote {args.output}")


if __name__ == "__main__":
    main()
