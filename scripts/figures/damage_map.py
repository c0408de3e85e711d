#!/usr/bin/python3
"""Damage of the discontinuities on the section (Figure 9 of the paper), from damage.csv.

Usage: /usr/bin/python3 scripts/figures/damage_map.py damage.csv [--section section.csv]
       [--plane y=10] [--band 2] -o damage_map.png

damage.csv (the last damage map of a DDA run; docs/dda-io.md): every contact that has been
closed, with its damage class. The contacts within `band` metres of the section plane are
drawn in the plane's (u, v) coordinates (x, z for a y= plane): opened contacts (cracks) red,
sliding orange, locked contacts whose bond is broken yellow, intact ones small and grey;
the opened and sliding ones sized by their opening and slip; the view frames the contacts.
With --section, the block outlines of section.csv are drawn underneath. Without --plane the plane is y at the middle
of the contacts' y range.
"""
import argparse

import numpy as np
from matplotlib.collections import LineCollection

from figure_io import add_scene_argument, number, plt, read_rows, save, unit_for

CLASSES = [("intact", "#9a9a9a", "intact (locked)"),
           ("bond_broken", "#e6c229", "bond broken (locked)"),
           ("sliding", "#e67e22", "sliding"),
           ("opened", "#c0392b", "opened")]
AXES = {"x": (1, 2), "y": (0, 2), "z": (0, 1)}  # plane normal -> (u, v) columns of (x, y, z)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv", help="damage.csv")
    parser.add_argument("--section", help="section.csv (block outlines underneath)")
    parser.add_argument("--plane", help="AXIS=VALUE, e.g. y=10")
    parser.add_argument("--band", type=float, default=2.0,
                        help="half-width of the slab of contacts drawn (m)")
    parser.add_argument("-o", "--output", default="damage_map.png")
    add_scene_argument(parser)
    args = parser.parse_args(argv)

    rows = read_rows(args.csv, ["x", "y", "z", "damage", "opening", "slip", "step", "time"])
    xyz = np.array([[number(r, k, args.csv, i) for k in ("x", "y", "z")]
                    for i, r in enumerate(rows, start=2)]).reshape(-1, 3)
    damage = np.array([r["damage"] for r in rows])
    size = np.array([max(number(r, "opening", args.csv, i), number(r, "slip", args.csv, i))
                     for i, r in enumerate(rows, start=2)])
    axis, value = "y", None
    if args.plane:
        axis, _, text = args.plane.partition("=")
        if axis not in AXES:
            raise SystemExit(f"--plane: expected x=, y= or z=, got {args.plane!r}")
        value = float(text)
    normal = "xyz".index(axis)
    if value is None:
        value = 0.5 * (xyz[:, normal].min() + xyz[:, normal].max()) if len(xyz) else 0.0
    u, v = AXES[axis]
    near = np.abs(xyz[:, normal] - value) <= args.band

    # The view frames the contacts (the DDA region), not the whole section around them; the
    # figure takes the region's shape (equal scales), with room for the legend below.
    lo = hi = None
    if near.any():
        lo = np.array([xyz[near, u].min(), xyz[near, v].min()])
        hi = np.array([xyz[near, u].max(), xyz[near, v].max()])
        lo, hi = lo - np.maximum(0.08 * (hi - lo), 2.0), hi + np.maximum(0.08 * (hi - lo), 2.0)
    shape = (hi[1] - lo[1]) / (hi[0] - lo[0]) if lo is not None else 0.5
    fig, ax = plt.subplots(figsize=(13, min(9.0, max(3.8, 11.0 * shape + 2.2))))
    if args.section:
        corners = {}
        for i, r in enumerate(read_rows(args.section, ["kind", "id", "part", "u", "v", "source"]),
                              start=2):
            if r["kind"] == "block":
                corners.setdefault((r["id"], r["part"]), []).append(
                    (number(r, "u", args.section, i), number(r, "v", args.section, i),
                     r["source"]))
        outline = [[(a, b), pts[(k + 1) % len(pts)][:2]] for pts in corners.values()
                   for k, (a, b, source) in enumerate(pts) if source != "fictitious"]
        ax.add_collection(LineCollection(outline, colors="#b0b0b0", linewidths=0.4))
    largest = size[near].max() if near.any() else 0.0
    scale, unit = unit_for([largest])
    for name, colour, label in CLASSES:
        pick = near & (damage == name)
        if not pick.any():
            continue
        if name in ("opened", "sliding") and largest > 0:
            marker = 6 + 60 * size[pick] / largest
        else:
            marker = 2 if name == "intact" else 8
        ax.scatter(xyz[pick, u], xyz[pick, v], s=marker, c=colour, edgecolors="none",
                   label=f"{label}: {pick.sum()}", zorder=3 if name != "intact" else 2)
    ax.autoscale_view()
    if lo is not None:
        ax.set_xlim(lo[0], hi[0])
        ax.set_ylim(lo[1], hi[1])
    ax.set_aspect("equal")
    names = "xyz"
    ax.set_xlabel(f"{names[u]} (m)")
    ax.set_ylabel(f"{names[v]} (m)")
    if near.any():
        fig.legend(fontsize=8, loc="lower center", ncol=4, markerscale=1.5,
                  title=f"marker size: opening or slip, largest {largest * scale:.3g} {unit}",
                  title_fontsize=8)
    step = rows[0]["step"] if rows else "-"
    time = number(rows[0], "time", args.csv, 2) if rows else 0.0
    ax.set_title(f"Damage of the discontinuities within {args.band:g} m of {axis} = {value:g} "
                 f"(step {step}, t = {time:.3g} s)")
    fig.tight_layout(rect=(0, 0.16, 1, 1))
    save(fig, args.output, scene=args.scene)
    print(f"damage_map: wrote {args.output}")


if __name__ == "__main__":
    main()
