#!/usr/bin/python3
"""Monitor displacement and velocity histories (Figure 8 of the paper).

Usage: /usr/bin/python3 scripts/figures/histories.py history.csv -o histories.png

history.csv (time,monitor,ux,uy,uz,vx,vy,vz): four panels against simulated time, one
line per monitor: horizontal displacement ux (x = downstream) and vertical displacement uz,
horizontal and vertical velocity vx and vz, as Figure 8(b)-(e); in cm and cm/s as the paper
when the values are that large, else in mm or um. A static run resets the velocities at
every step, so its velocity columns are all zero: the lower panels then show the rate of
each step's displacement, du/dt between two rows, and say so.
"""
import argparse

import numpy as np

from figure_io import add_scene_argument, number, plt, read_rows, save, unit_for


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv", help="history.csv")
    parser.add_argument("-o", "--output", default="histories.png")
    add_scene_argument(parser)
    args = parser.parse_args(argv)

    keys = ["time", "ux", "uz", "vx", "vz"]
    rows = read_rows(args.csv, ["time", "monitor", "ux", "uy", "uz", "vx", "vy", "vz"])
    series = {}
    for line, row in enumerate(rows, start=2):
        series.setdefault(row["monitor"], []).append(
            [number(row, k, args.csv, line) for k in keys])
    data = {monitor: np.array(points) for monitor, points in series.items()}
    # Static runs: no velocities in the file; the rate of the step displacements instead.
    rates = bool(data) and all(not np.any(d[:, 3:5]) for d in data.values())
    if rates:
        for d in data.values():
            dt = np.diff(d[:, 0])
            ok = dt > 0
            for u, v in ((1, 3), (2, 4)):
                d[1:, v] = np.where(ok, np.diff(d[:, u]) / np.where(ok, dt, 1.0), 0.0)
    fig, axes = plt.subplots(2, 2, figsize=(11, 7), sharex=True)
    speed = "rate of the step displacement" if rates else "velocity"
    panels = [("ux", "horizontal displacement ux", ""), ("uz", "vertical displacement uz", ""),
              ("vx", f"horizontal {speed} vx", "/s"), ("vz", f"vertical {speed} vz", "/s")]
    for ax, (key, label, per) in zip(axes.flat, panels):
        column = keys.index(key)
        scale, unit = unit_for(v for d in data.values() for v in d[:, column])
        for monitor, d in data.items():  # file order: the scene's monitor order
            ax.plot(d[:, 0], scale * d[:, column], lw=1.2, label=monitor)
        ax.set_ylabel(f"{label} ({unit}{per})")
        ax.grid(alpha=0.3)
    for ax in axes[1]:
        ax.set_xlabel("time (s)")
    axes[0][0].legend(fontsize=8, title="monitor")
    title = "Monitor histories"
    if rates:
        title += " (static run: velocities reset every step; lower panels du/dt of each step)"
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    save(fig, args.output, scene=args.scene)
    print(f"histories: wrote {args.output}")


if __name__ == "__main__":
    main()
