#!/usr/bin/python3
"""RQD-ball contour maps: RQD by scanline direction, one map per ball and threshold.

Usage: /usr/bin/python3 scripts/figures/rqd_ball_maps.py rqd_balls.csv -o rqd_ball_maps.png
       [--thresholds 1,3,5,7]

Equal-area (Lambert/Schmidt) lower-hemisphere projection of the scanline directions, north
up: a scanline is a line, so a direction pointing up is drawn as its opposite. The RQD of
each direction (%) is contoured (filled, 0 to 100) over the projection. Rows are balls,
columns thresholds (by default up to four, spread over the thresholds in the file).
"""
import argparse
import math

import numpy as np
from matplotlib.tri import Triangulation

from figure_io import number, plt, read_rows, save


def project(d):
    """Equal-area projection of axial unit vectors to the unit disc (x east, y north)."""
    d = np.where(d[:, 2:3] > 0, -d, d)
    r = np.sqrt(np.maximum(0.0, 1.0 + d[:, 2]))
    h = np.hypot(d[:, 0], d[:, 1])
    s = np.divide(r, h, out=np.zeros_like(r), where=h > 0)
    return d[:, 0] * s, d[:, 1] * s


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv", help="rqd_balls.csv")
    parser.add_argument("-o", "--output", default="rqd_ball_maps.png")
    parser.add_argument("--thresholds", default="", help="comma-separated thresholds (m)")
    args = parser.parse_args(argv)

    rows = read_rows(args.csv, ["ball", "dir_x", "dir_y", "dir_z", "threshold", "rqd"])
    data = {}
    for line, row in enumerate(rows, start=2):
        t = number(row, "threshold", args.csv, line)
        data.setdefault(row["ball"], {}).setdefault(t, []).append(
            [number(row, k, args.csv, line) for k in ("dir_x", "dir_y", "dir_z", "rqd")])
    balls = sorted(data)
    all_t = sorted({t for b in data.values() for t in b})
    if args.thresholds:
        wanted = [float(x) for x in args.thresholds.split(",") if x]
        chosen = [t for t in all_t if any(math.isclose(t, w) for w in wanted)]
    else:
        count = min(4, len(all_t))
        chosen = [all_t[round(i * (len(all_t) - 1) / max(1, count - 1))] for i in range(count)]
        chosen = sorted(set(chosen))
    fig, axes = plt.subplots(len(balls), len(chosen), figsize=(3.2 * len(chosen) + 1.0,
                                                               3.2 * len(balls)), squeeze=False)
    levels = np.linspace(0, 100, 11)
    image = None
    for i, ball in enumerate(balls):
        for j, t in enumerate(chosen):
            ax = axes[i][j]
            values = np.array(data[ball].get(t, []))
            ax.add_patch(plt.Circle((0, 0), 1, fill=False, lw=1))
            if len(values) >= 3:
                # Both ends of every scanline: the map is symmetric and has no seam.
                d = np.vstack([values[:, :3], -values[:, :3]])
                rqd = np.concatenate([values[:, 3], values[:, 3]])
                x, y = project(d)
                keep = np.hypot(x, y) <= 1.0 + 1e-9
                tri = Triangulation(x[keep], y[keep])
                image = ax.tricontourf(tri, rqd[keep], levels=levels, cmap="RdYlGn")
            ax.text(0, 1.04, "N", ha="center", va="bottom", fontsize=8)
            ax.set_title(f"{ball}, t = {t:g} m", fontsize=9)
            ax.set_aspect("equal")
            ax.set_xlim(-1.1, 1.1)
            ax.set_ylim(-1.1, 1.15)
            ax.axis("off")
    if image is not None:
        fig.colorbar(image, ax=axes, shrink=0.8, label="RQD (%)")
    fig.suptitle("RQD by scanline direction (equal-area, lower hemisphere)")
    save(fig, args.output)
    print(f"rqd_ball_maps: wrote {args.output}")


if __name__ == "__main__":
    main()
