#!/usr/bin/python3
"""Equal-area, lower-hemisphere stereonet of the fracture poles in fractures.csv.

Usage: /usr/bin/python3 scripts/figures/stereonet.py OUTDIR/fractures.csv [-o stereonet.png]
       [--max-poles N] [--sets J1,J2,...]

One panel per set: the poles (a random subsample of at most --max-poles, seeded, so the
figure is reproducible), density contours (1, 2, 4, 8, ... times uniform) from a kernel on
the sphere (Fisher kernel, kappa = 100) in multiples of a uniform density for a set of at
least MIN_CONTOURED discs (a kernel density of a few discs, such as a fault's, says
nothing), the mean pole (red star: the principal axis of the poles' orientation tensor, as
the poles are axes) and, in the title, the mean plane as dip direction / dip and Fisher's
kappa estimated as (N - 1) / (N - R) (R: the length of the resultant of the poles turned to
the mean's side; Fisher, Lewis and Embleton 1987, eq. 5.30). Equal-area (Schmidt/Lambert)
projection, lower hemisphere: a pole of trend T and plunge P sits at radius
sqrt(2) * sin((90 - P) / 2) from the centre, at azimuth T clockwise from north (up); N, E,
S, W are marked and a graticule of plunge circles (30 and 60 degrees) and trend lines
(every 30 degrees) is drawn. Reads only the CSV columns set, dip_direction and dip
(degrees).
"""
import argparse
import csv
import math
import sys

import numpy as np

from figure_io import add_scene_argument, compass, plt, save

# Fewest discs of a set for density contours.
MIN_CONTOURED = 10


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


def mean_and_kappa(p):
    """(mean pole as a lower-hemisphere unit vector, Fisher's kappa or None) of axial poles."""
    tensor = p.T @ p
    _, vectors = np.linalg.eigh(tensor)
    mean = vectors[:, -1]
    if mean[2] > 0:
        mean = -mean
    aligned = np.where((p @ mean)[:, None] < 0, -p, p)
    n = len(p)
    r = np.linalg.norm(aligned.sum(axis=0))
    kappa = (n - 1) / (n - r) if n >= 2 and n - r > 1e-12 else None
    return mean, kappa


def plane_of_pole(pole):
    """(dip direction, dip) in degrees of the plane whose lower-hemisphere pole is `pole`."""
    trend = math.degrees(math.atan2(pole[0], pole[1])) % 360.0
    plunge = math.degrees(math.asin(min(1.0, -pole[2])))
    return (trend + 180.0) % 360.0, 90.0 - plunge


def graticule(ax):
    """The primitive circle, plunge circles at 30 and 60 degrees, trend lines every 30
    degrees, and N, E, S, W."""
    for plunge in (30.0, 60.0):
        radius = math.sqrt(2.0) * math.sin(math.radians(90.0 - plunge) / 2.0)
        ax.add_patch(plt.Circle((0, 0), radius, fill=False, lw=0.4, color="#999", ls=":"))
    for trend in range(0, 360, 30):
        a = math.radians(trend)
        ax.plot([0.0, math.sin(a)], [0.0, math.cos(a)], lw=0.4, color="#999", ls=":")
    ax.add_patch(plt.Circle((0, 0), 1, fill=False, lw=1))
    compass(ax)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv", help="fractures.csv written by `rockmass dfn`")
    parser.add_argument("-o", "--output", default="stereonet.png")
    parser.add_argument("--max-poles", type=int, default=2000)
    parser.add_argument("--sets", default="", help="comma-separated set names (default: all)")
    add_scene_argument(parser)
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
    fig, axes = plt.subplots(rows, columns, figsize=(4.4 * columns, 4.4 * rows), squeeze=False)
    gx, gy, gv, inside = grid_vectors()
    facts = {}
    for ax, name in zip(axes.flat, names):
        data = np.asarray(by_set[name])
        every = poles(data[:, 0], data[:, 1])
        mean, kappa = mean_and_kappa(every)
        p = every
        if len(p) > args.max_poles:
            p = p[rng.choice(len(p), args.max_poles, replace=False)]
        contoured = len(data) >= MIN_CONTOURED
        if contoured:
            d = np.where(inside, density(p, gv), np.nan)
            top = max(2.0, float(np.nanmax(d)))
            levels = [2.0**k for k in range(0, int(math.log2(top)) + 1)] + [top]
            contours = ax.contourf(gx, gy, d, levels=levels, cmap="Blues", extend="neither")
            fig.colorbar(contours, ax=ax, shrink=0.6, label="multiples of uniform")
        graticule(ax)
        x, y = project(p)
        ax.plot(x, y, ".", ms=1.5 if contoured else 4, color="k", alpha=0.5)
        mx, my = project(mean)
        ax.plot(mx, my, "*", ms=12, color="#d62728", mec="k", mew=0.5)
        dip_direction, dip = plane_of_pole(mean)
        kappa_text = f"κ = {kappa:.3g}" if kappa is not None else "κ: -"
        note = "" if contoured else f" (no contours: fewer than {MIN_CONTOURED})"
        ax.set_title(f"{name}: {len(data)} discs{note}\nmean plane {dip_direction:03.0f}/"
                     f"{dip:02.0f} (dip dir./dip), Fisher {kappa_text}", fontsize=9)
        ax.set_aspect("equal")
        ax.set_xlim(-1.15, 1.15)
        ax.set_ylim(-1.15, 1.15)
        ax.axis("off")
        facts[name] = {"discs": len(data), "contoured": contoured,
                       "mean_dip_direction": round(dip_direction, 1), "mean_dip": round(dip, 1),
                       "kappa": None if kappa is None else round(kappa, 2)}
    for ax in list(axes.flat)[len(names):]:
        ax.axis("off")
    fig.suptitle("Poles of the fracture sets, equal-area lower hemisphere (red star: mean pole;"
                 " dotted: plunge 30° and 60°, trend every 30°)", fontsize=10)
    fig.tight_layout()
    save(fig, args.output, facts={"sets": facts}, scene=args.scene)
    print(f"stereonet: wrote {args.output} ({len(names)} sets)")


if __name__ == "__main__":
    main()
