#!/usr/bin/python3
"""Equal-area, lower-hemisphere stereonet of the fracture poles in fractures.csv.

Usage: /usr/bin/python3 scripts/figures/stereonet.py OUTDIR/fractures.csv [-o stereonet.png]
       [--max-poles N] [--sets J1,J2,...]

One panel per joint set: the poles (a random subsample of at most --max-poles, seeded, so
the figure is reproducible) and density contours (1, 2, 4, 8, ... times uniform) from a Gaussian kernel on the
sphere (Fisher kernel, kappa = 100), in multiples of a uniform density. Equal-area
(Schmidt/Lambert) projection: a pole of trend T and plunge P sits at radius
sqrt(2) * sin((90 - P) / 2) from the centre, at azimuth T clockwise from north (up).
Reads only the CSV columns set, dip_direction and dip (degrees).
"""
import argparse
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def poles(dip_direction, dip):
    """Lower-hemisphere pole vectors (east, north, up) of planes given in degrees."""
    trend = np.radians(np.asarray(dip_direction) + 180.0)
    plunge = np.radians(90.0 - np.asarray(dip))
    return np.stack([np.cos(plunge) * np.sin(trend), np.cos(plunge) * np.cos(trend),
                     -np.sin(plunge)], axis=-1)


def project(v):
    """Equal-area projection of lower-hemisphere unit vectors to the unit disc (x east, y north)."""
    v = np.where(v[..., 2:3] > 0, -v, v)  # axial data: flip to the lower hemisphere
    r = np.sqrt(np.maximum(0.0, 1.0 + v[..., 2]))  # = sqrt(2) sin(theta/2), theta from nadir
    horizontal = np.hypot(v[..., 0], v[..., 1])
    scale = np.divide(r, horizontal, out=np.zeros_like(r), where=horizontal > 0)
    return v[..., 0] * scale, v[..., 1] * scale


def grid_vectors(n=121):
    """Unit vectors of the lower hemisphere on an n x n grid of the projection disc."""
    x, y = np.meshgrid(np.linspace(-1, 1, n), np.linspace(-1, 1, n))
    r2 = x * x + y * y
    inside = r2 <= 1.0
    # inverse equal-area: r = sqrt(1 + z) with z <= 0, so z = r^2 - 1.
    z = r2 - 1.0
    horizontal = np.sqrt(np.maximum(0.0, 1.0 - z * z))
    r = np.sqrt(r2)
    scale = np.divide(horizontal, r, out=np.zeros_like(r), where=r > 0)
    v = np.stack([x * scale, y * scale, z], axis=-1)
    return x, y, v, inside


def density(pole_vectors, v, kappa=100.0):
    """Axial Fisher-kernel density on the sphere, in multiples of a uniform density."""
    dots = np.abs(v.reshape(-1, 3) @ pole_vectors.T)
    # Normalised so that a uniform distribution gives 1: the kernel exp(kappa (|c| - 1)) has
    # mean (1 - exp(-kappa)) / kappa over the sphere (|c| uniform on [0, 1]).
    kernel = np.exp(kappa * (dots - 1.0)).mean(axis=1) * kappa / (1.0 - math.exp(-kappa))
    return kernel.reshape(v.shape[:-1])


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv", help="fractures.csv written by `rockmass dfn`")
    parser.add_argument("-o", "--output", default="stereonet.png")
    parser.add_argument("--max-poles", type=int, default=2000)
    parser.add_argument("--sets", default="", help="comma-separated set names (default: all)")
    args = parser.parse_args()

    by_set = {}
    with open(args.csv, newline="") as f:
        for line, row in enumerate(csv.DictReader(f), start=2):
            try:
                by_set.setdefault(row["set"], []).append(
                    (float(row["dip_direction"]), float(row["dip"])))
            except (KeyError, ValueError) as e:
                sys.exit(f"{args.csv}:{line}: expected set, dip_direction, dip columns ({e})")
    names = [s for s in args.sets.split(",") if s] or sorted(by_set)
    names = [s for s in names if s in by_set]
    if not names:
        sys.exit(f"{args.csv}: no fractures of the requested sets")

    rng = np.random.default_rng(12345)
    columns = min(3, len(names))
    rows = math.ceil(len(names) / columns)
    fig, axes = plt.subplots(rows, columns, figsize=(4 * columns, 4.2 * rows), squeeze=False)
    gx, gy, gv, inside = grid_vectors()
    for ax, name in zip(axes.flat, names):
        data = np.asarray(by_set[name])
        p = poles(data[:, 0], data[:, 1])
        if len(p) > args.max_poles:
            p = p[rng.choice(len(p), args.max_poles, replace=False)]
        d = np.where(inside, density(p, gv), np.nan)
        top = max(2.0, float(np.nanmax(d)))
        levels = [2.0**k for k in range(0, int(math.log2(top)) + 1)] + [top]
        contours = ax.contourf(gx, gy, d, levels=levels, cmap="Blues", extend="neither")
        x, y = project(p)
        ax.plot(x, y, ".", ms=1.5, color="k", alpha=0.5)
        ax.add_patch(plt.Circle((0, 0), 1, fill=False, lw=1))
        ax.text(0, 1.04, "N", ha="center", va="bottom")
        ax.set_title(f"{name}: {len(data)} discs", fontsize=10)
        ax.set_aspect("equal")
        ax.set_xlim(-1.1, 1.1)
        ax.set_ylim(-1.1, 1.15)
        ax.axis("off")
        fig.colorbar(contours, ax=ax, shrink=0.7, label="multiples of uniform")
    for ax in list(axes.flat)[len(names):]:
        ax.axis("off")
    fig.suptitle("Poles, equal-area lower hemisphere")
    fig.tight_layout()
    fig.savefig(args.output, dpi=120)
    print(f"stereonet: wrote {args.output} ({len(names)} sets)")


if __name__ == "__main__":
    main()
