#!/usr/bin/python3
"""report.html: one self-contained page of a rockmass run (opened from disk, offline) with the
summary, the figures and a 3D viewer (three.js from Debian's libjs-three, inlined).

Usage: /usr/bin/python3 scripts/report/make_report.py OUTDIR [--three DIR] [-o report.html]

Reads only the files `rockmass run` writes into OUTDIR: summary.json, the PNG figures it lists,
blocks.csv (every block: id, volume, material, bounding box), fractures.csv (the discs, by set),
rqd_balls.csv with summary.json's balls (each ball's RQD per direction and threshold),
summary.json's monitors, and the DDA frames of dda.pvd (each DDA block's bounding box and
centroid displacement per frame). The viewer draws every block as its bounding box, one
instanced mesh for the whole model (so that the 42 786 blocks of the full Xiangjiaba model
stay one draw call), coloured by material, by volume (log) or, for the DDA's blocks, by
displacement at the frame the slider picks; the discs as instanced ellipses coloured by set
(the 20 000 largest when there are more); each RQD ball as points at RQD / 100 of its radius in
every direction for the threshold chosen; the monitors as spheres. Clicking a block shows its
id, volume and material. With `?test` in the URL the page writes what it drew and any script
error into <pre id="status"> (JSON), and with `&pick=X,Y` (pixels of the canvas) it picks
there first (tests/report/report_test.py reads it from headless Chromium's DOM).
"""
import argparse
import base64
import csv
import json
import math
import os
import re
import sys
import xml.etree.ElementTree as ET
import zlib

import numpy as np

MAX_DISCS = 20000
MAX_FRAMES = 60


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def vtu_array(element, header_type):
    """A DataArray of a VTU written with vtkZLibDataCompressor (binary, inline): the base64
    header (block count, block size, last block size, compressed sizes), then the base64 of
    the compressed blocks."""
    text = "".join(element.text.split())
    size = 8 if header_type == "UInt64" else 4
    kind = "<u8" if size == 8 else "<u4"
    first = np.frombuffer(base64.b64decode(text[:((size + 2) // 3) * 4])[:size], kind)[0]
    header_chars = ((3 + int(first)) * size + 2) // 3 * 4
    header = np.frombuffer(base64.b64decode(text[:header_chars])[:(3 + int(first)) * size], kind)
    blocks = int(header[0])
    data = base64.b64decode(text[header_chars:])
    out, at = [], 0
    for c in header[3:3 + blocks]:
        out.append(zlib.decompress(data[at:at + int(c)]))
        at += int(c)
    types = {"Float64": "<f8", "Float32": "<f4", "Int32": "<i4", "Int64": "<i8", "UInt8": "u1",
             "UInt32": "<u4", "UInt64": "<u8"}
    values = np.frombuffer(b"".join(out), types[element.get("type")])
    components = int(element.get("NumberOfComponents", "1"))
    return values.reshape(-1, components) if components > 1 else values


def frame_boxes(path, boxes=True):
    """Per DDA block of one frame: ids, bounding boxes (n x 6; None unless `boxes`) and
    centroid displacement."""
    root = ET.parse(path).getroot()
    header = root.get("header_type", "UInt32")
    piece = root.find("UnstructuredGrid/Piece")
    arrays = {}
    for section in ("Points", "Cells", "CellData"):
        for e in piece.find(section).iter("DataArray"):
            arrays[e.get("Name") or section] = (e, section)
    block = vtu_array(arrays["block"][0], header).astype(np.int64)
    displacement = vtu_array(arrays["displacement"][0], header).reshape(-1, 3)
    ids, cell_block = np.unique(block, return_inverse=True)
    first = np.zeros(len(ids), dtype=np.int64)
    first[cell_block[::-1]] = np.arange(len(block))[::-1]
    u = np.linalg.norm(displacement[first], axis=1)
    if not boxes:
        return ids, None, u
    if len(ids) == 0:
        return ids, np.empty((0, 6)), u
    points = vtu_array(arrays["Points"][0], header).reshape(-1, 3)
    connectivity = vtu_array(arrays["connectivity"][0], header).astype(np.int64)
    offsets = vtu_array(arrays["offsets"][0], header).astype(np.int64)
    cell = np.repeat(np.arange(len(offsets)), np.diff(offsets, prepend=0))
    # Each block's points together (a stable sort by block), then the least and largest
    # coordinates of each run; reduceat needs every block to own a point (a run per block).
    per_point_block = cell_block[cell]
    order = np.argsort(per_point_block, kind="stable")
    corners = points[connectivity][order]
    starts = np.searchsorted(per_point_block[order], np.arange(len(ids)))
    if starts[-1] >= len(corners) or not (np.diff(starts) > 0).all():
        sys.exit(f"{path}: a DDA block of the frame has no point")
    low = np.minimum.reduceat(corners, starts, axis=0)
    high = np.maximum.reduceat(corners, starts, axis=0)
    return ids, np.hstack([low, high]), u


def dda_frames(out):
    pvd = os.path.join(out, "dda.pvd")
    if not os.path.exists(pvd):
        return None
    entries = [(float(e.get("timestep")), e.get("file"))
               for e in ET.parse(pvd).getroot().iter("DataSet")]
    if not entries:
        return None
    if len(entries) > MAX_FRAMES:  # evenly, the first and the last kept
        keep = np.linspace(0, len(entries) - 1, MAX_FRAMES).round().astype(int)
        entries = [entries[k] for k in sorted(set(keep))]
    # The first frame gives the boxes and its displacements; the others their displacements.
    ids, boxes, first_u = frame_boxes(os.path.join(out, entries[0][1]))
    times, magnitudes = [], []
    for k, (t, name) in enumerate(entries):
        if k == 0:
            frame_ids, u = ids, first_u
        else:
            frame_ids, _, u = frame_boxes(os.path.join(out, name), boxes=False)
        if not np.array_equal(frame_ids, ids):
            sys.exit(f"{name}: the frames hold different blocks")
        times.append(t)
        magnitudes.append([float(x) for x in u])
    return {"times": times, "id": ids.tolist(), "box": boxes.ravel().round(4).tolist(),
            "displacement": magnitudes}


def blocks_of(out, summary):
    path = os.path.join(out, "blocks.csv")
    if not os.path.exists(path):
        return None
    table = rows(path)
    names = summary.get("material_names") or sorted({r["material"] for r in table})
    index = {n: k for k, n in enumerate(names)}
    box = []
    for r in table:
        box += [float(r[k]) for k in ("xmin", "ymin", "zmin", "xmax", "ymax", "zmax")]
    return {"id": [int(r["id"]) for r in table], "volume": [float(r["volume"]) for r in table],
            "material": [index.get(r["material"], -1) for r in table], "materials": names,
            "structure": [r.get("structure", "") != "" for r in table],
            "box": [round(v, 4) for v in box]}


def discs_of(out):
    path = os.path.join(out, "fractures.csv")
    if not os.path.exists(path):
        return None
    table = rows(path)
    total = len(table)
    if total > MAX_DISCS:
        table = sorted(table, key=lambda r: -float(r["a"]))[:MAX_DISCS]
    sets = sorted({r["set"] for r in table})
    data = {"sets": sets, "total": total, "center": [], "normal": [], "major": [], "a": [],
            "b": [], "set": []}
    for r in table:
        dd, dip = math.radians(float(r["dip_direction"])), math.radians(float(r["dip"]))
        data["center"] += [round(float(r[k]), 3) for k in ("cx", "cy", "cz")]
        data["normal"] += [round(math.sin(dip) * math.sin(dd), 5),
                           round(math.sin(dip) * math.cos(dd), 5), round(math.cos(dip), 5)]
        data["major"] += [round(float(r[k]), 5) for k in ("major_x", "major_y", "major_z")]
        data["a"].append(round(float(r["a"]), 3))
        data["b"].append(round(float(r["b"]), 3))
        data["set"].append(sets.index(r["set"]))
    return data


def balls_of(out, summary):
    path = os.path.join(out, "rqd_balls.csv")
    balls = summary.get("balls") or []
    if not balls or not os.path.exists(path):
        return []
    table = rows(path)
    result = []
    for ball in balls:
        mine = [r for r in table if r["ball"] == ball["name"]]
        thresholds = sorted({float(r["threshold"]) for r in mine})
        directions, rqd = [], {t: [] for t in thresholds}
        for r in mine:
            t = float(r["threshold"])
            if t == thresholds[0]:
                directions += [round(float(r[k]), 5) for k in ("dir_x", "dir_y", "dir_z")]
            rqd[t].append(round(float(r["rqd"]), 2))
        result.append({"name": ball["name"], "center": ball["center"],
                       "radius": ball.get("radius", ball.get("length", 1) / 2),
                       "thresholds": thresholds, "directions": directions,
                       "rqd": [rqd[t] for t in thresholds]})
    return result


def facts_of(summary):
    facts = [("scene", summary.get("name", "")), ("seed", summary.get("seed", "")),
             ("stages", ", ".join(summary.get("stages", [])))]
    for key, label in (("discs", "discs"), ("blocks", "blocks"), ("safety_factor", "K_s"),
                       ("unknowns", "DDA unknowns")):
        if key in summary:
            facts.append((label, summary[key]))
    srf = (summary.get("strength_reduction") or {}).get("critical_srf")
    if srf is not None:
        facts.append(("critical SRF", srf))
    return facts


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("outdir")
    parser.add_argument("--three", default="/usr/share/javascript/three",
                        help="libjs-three's folder (three.min.js, examples/js/controls)")
    parser.add_argument("-o", "--output", help="default OUTDIR/report.html")
    args = parser.parse_args(argv)
    out = args.outdir
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    try:
        with open(os.path.join(args.three, "three.min.js")) as f:
            three = f.read()
        with open(os.path.join(args.three, "examples/js/controls/OrbitControls.js")) as f:
            orbit = f.read()
    except FileNotFoundError as e:
        sys.exit(f"report: {e.filename}: three.js not found (Debian's libjs-three)")
    figures = []
    for name in (summary.get("run") or {}).get("figures", []):
        path = os.path.join(out, name)
        if os.path.exists(path):
            with open(path, "rb") as f:
                figures.append({"name": name, "png": base64.b64encode(f.read()).decode()})
    domain = summary.get("domain") or (summary.get("run") or {}).get("domain") or {}
    monitors = [{"name": m["name"], "point": m["point"]} for m in summary.get("monitors", [])
                if "point" in m]
    data = {"name": summary.get("name", ""), "facts": facts_of(summary), "figures": figures,
            "domain": domain, "blocks": blocks_of(out, summary), "discs": discs_of(out),
            "balls": balls_of(out, summary), "monitors": monitors, "frames": dda_frames(out)}
    with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "report.html")) as f:
        page = f.read()
    payload = json.dumps(data, separators=(",", ":")).replace("</", "<\\/")
    page = page.replace("/*THREE*/", three.replace("</script", "<\\/script"))
    page = page.replace("/*ORBIT*/", orbit.replace("</script", "<\\/script"))
    page = page.replace("/*DATA*/", payload)
    page = re.sub(r"<title>.*?</title>", f"<title>{summary.get('name', 'rockmass')}: rockmass "
                  "report</title>", page, count=1)
    target = args.output or os.path.join(out, "report.html")
    with open(target + ".tmp", "w") as f:
        f.write(page)
    os.replace(target + ".tmp", target)
    print("report: " + os.path.basename(target))


if __name__ == "__main__":
    main()
