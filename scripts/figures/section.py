#!/usr/bin/python3
"""Vertical section through the 3D model (Figure 5 of the paper), from section.csv.

Usage: /usr/bin/python3 scripts/figures/section.py section.csv -o section.png

section.csv (kind,id,label,part,vertex,u,v,x,y,z,source; docs/scene-reference.md): the
block pieces filled by material, block outlines (every edge whose source is not
`fictitious`), joint traces (blue; discs that do not cut blocks light), faults (red) and
interlayers (brown, thick), in the plane's (u, v) coordinates with equal scales.
"""
import argparse

from matplotlib.collections import LineCollection, PolyCollection

from figure_io import number, plt, read_rows, save

FILLS = ["#e8dcc4", "#d9e4ee", "#e3ecd5", "#f0d9d9", "#e6dff0", "#f2ebcf", "#d6ece9", "#ece0d2"]
TRACES = {"joint": ("#1f4e9a", 0.6), "fab": ("#1f4e9a", 0.6), "fault": ("#c0392b", 1.4),
          "interlayer": ("#8b5a2b", 2.2)}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv", help="section.csv")
    parser.add_argument("-o", "--output", default="section.png")
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
    fig, ax = plt.subplots(figsize=(12, 6))
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
    ax.set_xlabel("u (m)")
    ax.set_ylabel("v (m)")
    ax.legend(fontsize=8, loc="upper right")
    ax.set_title(f"Section: {len(polygons)} piece sections, {len(traces)} traces")
    fig.tight_layout()
    save(fig, args.output)
    print(f"section: wrote {args.output}")


if __name__ == "__main__":
    main()
