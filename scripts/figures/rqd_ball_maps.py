#!/usr/bin/python3
"""RQD-ball contour maps: RQD by scanline direction, one map per ball and threshold.

Usage: /usr/bin/python3 scripts/figures/rqd_ball_maps.py rqd_balls.csv -o rqd_ball_maps.png
       [--thresholds 1,3,5,7]

Equal-area (Lambert/Schmidt) lower-hemisphere projection of the scanline directions, north
up: a scanline is a line, so a direction pointing up is drawn as its opposite. The RQD of
each direction (%) is contoured (filled, 0 to 100) over the projection. Rows are balls,
columns thresholds: by default the (at most four) informative ones, those at which the RQD
differs most between directions (the largest standard deviation over the directions,
averaged over the balls), in ascending order; a threshold at which every direction gives
about the same RQD (all near 100 % at small t, all near 0 at large t) is a flat map. The
mean RQD over the directions of each ball is in each panel's title.
"""
import argparse
import math

import numpy as np
from matplotlib.tri import Triangulation

from figure_io import add_scene_argument, compass, number, plt, read_rows, save


def project(d):
    """Equal-area projection of axial unit vectors to the unit disc (x east, y north)."""
    d = np.where(d[:, 2:3] > 0, -d, d)
    r = np.sqrt(np.maximum(0.0, 1.0 + d[:, 2]))
    h = np.hypot(d[:, 0], d[:, 1])
    s = np.divide(r, h, out=np.zeros_like(r), where=h > 0)
    return d[:, 0] * s, d[:, 1] * s


def informative(data, thresholds, count=4):
    """The `count` thresholds with the largest spread of RQD over the directions (standard
    deviation, averaged over the balls), ascending."""
    spread = {}
    for t in thresholds:
        deviations = [np.std([row[3] for row in by_t[t]]) for by_t in data.values() if by_t.get(t)]
        spread[t] = float(np.mean(deviations)) if deviations else 0.0
    best = sorted(thresholds, key=lambda t: (-spread[t], t))[:count]
    return sorted(best)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv", help="rqd_balls.csv")
    parser.add_argument("-o", "--output", default="rqd_ball_maps.png")
    parser.add_argument("--thresholds", default="", help="comma-separated thresholds (m)")
    add_scene_argument(parser)
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
        chosen = informative(data, all_t)
    fig, axes = plt.subplots(len(balls), len(chosen), figsize=(3.2 * len(chosen) + 1.0,
                                                               3.2 * len(balls)), squeeze=False)
    # The top level just above 100 so that directions at exactly 100 % are filled.
    levels = np.append(np.linspace(0, 90, 10), 100.0 + 1e-6)
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
            compass(ax, fontsize=7)
            mean = f", mean {values[:, 3].mean():.0f} %" if len(values) else ""
            ax.set_title(f"{ball}, t = {t:g} m{mean}", fontsize=9)
            ax.set_aspect("equal")
            ax.set_xlim(-1.1, 1.1)
            ax.set_ylim(-1.1, 1.15)
            ax.axis("off")
    if image is not None:
        fig.colorbar(image, ax=axes, shrink=0.8, label="RQD (%)")
    rule = "given" if args.thresholds else "the thresholds at which the directions differ most"
    fig.suptitle(f"RQD by scanline direction (equal-area, lower hemisphere); t: {rule}",
                 fontsize=10)
    save(fig, args.output, facts={"thresholds": chosen, "all_thresholds": all_t, "rule": rule},
         scene=args.scene)
    print(f"rqd_ball_maps: wrote {args.output}")


if __name__ == "__main__":
    main()
