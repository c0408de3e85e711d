#!/usr/bin/python3
"""Monitor displacement and velocity histories (Figure 8 of the paper).

Usage: /usr/bin/python3 scripts/figures/histories.py history.csv -o histories.png

history.csv (time,monitor,ux,uy,uz,vx,vy,vz): four panels against simulated time, one
line per monitor: horizontal displacement ux (x = downstream) and vertical displacement uz
in cm, horizontal and vertical velocity vx and vz in cm/s, as Figure 8(b)-(e).
"""
import argparse

import numpy as np

from figure_io import number, plt, read_rows, save


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv", help="history.csv")
    parser.add_argument("-o", "--output", default="histories.png")
    args = parser.parse_args(argv)

    keys = ["time", "ux", "uz", "vx", "vz"]
    rows = read_rows(args.csv, ["time", "monitor", "ux", "uy", "uz", "vx", "vy", "vz"])
    series = {}
    for line, row in enumerate(rows, start=2):
        series.setdefault(row["monitor"], []).append(
            [number(row, k, args.csv, line) for k in keys])
    fig, axes = plt.subplots(2, 2, figsize=(11, 7), sharex=True)
    panels = [("ux", "horizontal displacement ux (cm)"), ("uz", "vertical displacement uz (cm)"),
              ("vx", "horizontal velocity vx (cm/s)"), ("vz", "vertical velocity vz (cm/s)")]
    for ax, (key, label) in zip(axes.flat, panels):
        column = keys.index(key)
        for monitor in series:  # file order: the scene's monitor order
            data = np.array(series[monitor])
            ax.plot(data[:, 0], 100.0 * data[:, column], lw=1.2, label=monitor)
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
    for ax in axes[1]:
        ax.set_xlabel("time (s)")
    axes[0][0].legend(fontsize=8, title="monitor")
    fig.suptitle("Monitor histories")
    fig.tight_layout()
    save(fig, args.output)
    print(f"histories: wrote {args.output}")


if __name__ == "__main__":
    main()
