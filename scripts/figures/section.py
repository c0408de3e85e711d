#!/usr/bin/python3
"""Vertical section through the 3D model (Figure 5 of the paper), from section.csv.

Usage: /usr/bin/python3 scripts/figures/section.py section.csv -o section.png

section.csv (kind,id,label,part,vertex,u,v,x,y,z,source; docs/scene-reference.md): the
block pieces filled by material, block outlines (every edge whose source is not
`fictitious`), joint traces (blue; discs that do not cut blocks light), faults (red) and
interlayers (brown, thick), in the plane's (u, v) coordinates with equal scales. The plane
and the axes are named from the file: the coordinate that is the same on every row names the
plane ("y = 10 m"), and u and v are labelled with the model axes they follow (x, z). Top:
the whole section. Bottom: the rock (the band of v the fracture traces span, as discs cut the
rock only) enlarged, so that a thin foundation under a tall dam is not a strip a few pixels
high.
"""
import argparse

from matplotlib.collections import LineCollection, PolyCollection

from figure_io import add_scene_argument, number, plt, read_rows, save

FILLS = ["#e8dcc4", "#d9e4ee", "#e3ecd5", "#f0d9d9", "#e6dff0", "#f2ebcf", "#d6ece9", "#ece0d2"]
TRACES = {"joint": ("#1f4e9a", 0.6), "fab": ("#1f4e9a", 0.6), "fault": ("#c0392b", 1.4),
          "interlayer": ("#8b5a2b", 2.2)}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv", help="section.csv")
    parser.add_argument("-o", "--output", default="section.png")
    add_scene_argument(parser)
    args = parser.parse_args(argv)

    rows = read_rows(args.csv, ["kind", "id", "label", "part", "vertex", "u", "v", "source"])
    polygons = {}  # (block, piece) -> (material, [(u, v, source)])
    traces = {}    # (kind, id, part) -> (source, [(u, v)])
    for line, row in enumerate(rows, start=2):
        uv = (number(row, "u", args.csv, line), number(row, "v", args.csv, line))
        if row["kind"] == "block":
            polygons.setdefault((row["id"], row["part"]), (row["label"], []))[1].append(
                (*uv, row["source"]))
        else:
            traces.setdefault((row["kind"], row["id"], row["part"]), (row["source"], []))[
                1].append(uv)
    materials = sorted({m for m, _ in polygons.values()})
    plane, u_axis, v_axis = plane_of(rows, args.csv)
    fig, (ax, zoom) = plt.subplots(2, 1, figsize=(12, 10), height_ratios=[1, 1])
    draw(ax, polygons, traces, materials)
    draw(zoom, polygons, traces, materials)
    ax.legend(fontsize=8, loc="upper right")
    for a in (ax, zoom):
        a.set_xlabel(f"{u_axis} (m)")
        a.set_ylabel(f"{v_axis} (m)")
    ax.set_title(f"Whole section: {len(polygons)} piece sections, {len(traces)} traces",
                 fontsize=10)
    # The rock's extent: the traces (discs cut the rock only) and the pieces they touch.
    rock_v = [v for (_, pts) in traces.values() for _, v in pts]
    if rock_v:
        low, high = min(rock_v), max(rock_v)
        pad = 0.05 * (high - low) + 1e-9
        zoom.set_ylim(low - pad, high + pad)
        zoom.set_title(f"Rock: {v_axis} from {round(low, 6):g} to {round(high, 6):g} m, "
                       "enlarged", fontsize=10)
    fig.suptitle(f"Vertical section in the plane {plane}", fontsize=11)
    fig.tight_layout()
    save(fig, args.output, facts={"plane": plane, "u": u_axis, "v": v_axis}, scene=args.scene)
    print(f"section: wrote {args.output}")


def plane_of(rows, path):
    """('y = 10 m', 'x', 'z'): the model coordinate constant on every row, and the model
    axes that u and v follow (from the x, y, z columns; 'u', 'v' when there are none)."""
    if not rows or not all(k in rows[0] for k in ("x", "y", "z")):
        return "of section.csv", "u", "v"
    columns = {a: [number(r, a, path, i) for i, r in enumerate(rows, start=2)]
               for a in ("x", "y", "z", "u", "v")}
    plane = "of section.csv"
    for a in ("x", "y", "z"):
        values = columns[a]
        if max(values) - min(values) <= 1e-9 * max(1.0, max(abs(v) for v in values)):
            plane = f"{a} = {values[0]:g} m"
    names = []
    for w in ("u", "v"):
        same = [a for a in ("x", "y", "z")
                if all(abs(p - q) <= 1e-9 * max(1.0, abs(q))
                       for p, q in zip(columns[w], columns[a]))]
        names.append(same[0] if same else w)
    return plane, names[0], names[1]


def draw(ax, polygons, traces, materials):
    """The pieces, their outlines and the traces on one panel, with equal scales."""
    for i, material in enumerate(materials):
        shapes = [[(u, v) for u, v, _ in pts] for m, pts in polygons.values() if m == material]
        ax.add_collection(PolyCollection(shapes, facecolors=FILLS[i % len(FILLS)],
                                         edgecolors="none", label=material))
    outline = []
    for _, pts in polygons.values():
        for k, (u, v, source) in enumerate(pts):
            if source != "fictitious":
                u2, v2, _ = pts[(k + 1) % len(pts)]
                outline.append([(u, v), (u2, v2)])
    ax.add_collection(LineCollection(outline, colors="#404040", linewidths=0.4))
    for kind in ("joint", "fab", "fault", "interlayer"):
        for cutting in (False, True):
            segments = [pts for (k, _, _), (source, pts) in traces.items()
                        if k == kind and (source == "cutting") == cutting]
            if not segments:
                continue
            colour, width = TRACES[kind]
            if kind in ("joint", "fab") and not cutting:
                colour, width = "#8fb3e0", 0.4
            name = kind if cutting else f"{kind} (RQD only)"
            ax.add_collection(LineCollection(segments, colors=colour, linewidths=width,
                                             label=name))
    ax.autoscale_view()
    ax.set_aspect("equal")


if __name__ == "__main__":
    main()
