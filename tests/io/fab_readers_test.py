#!/usr/bin/python3
"""fractures.fab read as the public FAB readers read it (FracMan's format as pyfracman's
`parse_fab_file` and porepy's `network_3d_from_fab` parse it, neither of them on Debian):
every line of FORMAT, PROPERTIES and SETS is "key = value" (both readers split on '='), a
property's name is the quoted string of its line (pyfracman), sets are "Set<k> = \"name\"",
each fracture header is "id nvertices set values...", one value per property (pyfracman
builds its property table from them), vertex lines "k x y z", a normal line "0 nx ny nz",
and a TESSFRACTURE section (porepy's return_all reads it). The values are checked against
fractures.csv and summary.json.

Usage: fab_readers_test.py ROCKMASS_BINARY
"""
import csv
import json
import os
import subprocess
import sys
import tempfile

SCENE = """version: 1
name: fab-check
seed: 11
domain:
  box: {min: [0, 0, -10], max: [20, 20, 0]}
materials:
  rock: {density: 2650, young: 7.0e9, poisson: 0.25}
rock_material: rock
joints:
  rj: {friction: 0.86, cohesion: 0}
default_joint: rj
joint_sets:
  - name: J1
    orientation: {distribution: fisher, dip_direction: 90, dip: 60, kappa: 50}
    spacing: {distribution: lognormal, mean: 3.0, std: 1.0}
    trace_length: {distribution: lognormal, mean: 15.0, std: 5.0}
  - name: J2
    orientation: {distribution: fisher, dip_direction: 200, dip: 30, kappa: 40}
    spacing: {distribution: lognormal, mean: 4.0, std: 1.0}
    trace_length: {distribution: lognormal, mean: 10.0, std: 3.0}
faults:
  - {name: F1, center: [10, 10, -5], dip_direction: 0, dip: 80}
"""


def sections(lines):
    """{name: [lines]} of the BEGIN/END sections (top level), in file order."""
    found = {}
    name = None
    for raw in lines:
        line = raw.strip()
        if name is None:
            if not line:
                continue
            if not line.startswith("BEGIN "):
                raise ValueError(f"expected BEGIN, got {line!r}")
            name = line[6:].strip()
            found[name] = []
        elif line == "END " + name:
            name = None
        else:
            found[name].append(line)
    if name is not None:
        raise ValueError(f"section {name} not ended")
    return found


def key_values(lines, section):
    """The "key = value" lines of a section, as both readers split them."""
    result = {}
    for line in lines:
        words = line.split("=")
        if len(words) < 2:
            raise ValueError(f"{section}: {line!r} is not 'key = value'")
        result[words[0].strip()] = words[1].strip()
    return result


def main():
    binary = sys.argv[1]
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        scene = os.path.join(tmp, "scene.yaml")
        with open(scene, "w") as f:
            f.write(SCENE)
        out = os.path.join(tmp, "out")
        subprocess.run([binary, "dfn", scene, "-o", out], check=True, capture_output=True)
        with open(os.path.join(out, "fractures.fab")) as f:
            parts = sections(f.read().split("\n"))
        with open(os.path.join(out, "fractures.csv"), newline="") as f:
            discs = list(csv.DictReader(f))
        with open(os.path.join(out, "summary.json")) as f:
            summary = json.load(f)
        for name in ("FORMAT", "PROPERTIES", "SETS", "FRACTURE", "TESSFRACTURE"):
            if name not in parts:
                failures.append(f"no {name} section ({list(parts)})")
        fmt = key_values(parts.get("FORMAT", []), "FORMAT")
        props = key_values(parts.get("PROPERTIES", []), "PROPERTIES")
        # pyfracman: the name is what the double quotes enclose.
        prop_names = [v.split('"')[1] for v in props.values()]
        if prop_names != ["Semi-major axis (m)", "Semi-minor axis (m)"]:
            failures.append(f"properties {prop_names}")
        if int(fmt.get("No_Properties", -1)) != len(prop_names):
            failures.append(f"No_Properties {fmt.get('No_Properties')}, {len(prop_names)} listed")
        sets = key_values(parts.get("SETS", []), "SETS")
        set_names = [sets.get(f"Set{k + 1}", "").replace('"', "") for k in range(len(sets))]
        expected_sets = [s["name"] for s in summary["sets"]]
        if set_names != expected_sets:
            failures.append(f"sets {set_names}, summary.json {expected_sets}")
        lines = parts.get("FRACTURE", [])
        at = 0
        read = []
        nodes = 0
        while at < len(lines):
            fid, nvert, set_no, *values = lines[at].split()
            nvert = int(nvert)
            vertices = [list(map(float, lines[at + 1 + k].split()[1:])) for k in range(nvert)]
            normal = lines[at + 1 + nvert].split()
            if normal[0] != "0" or len(normal) != 4:
                failures.append(f"fracture {fid}: normal line {normal}")
            read.append((int(fid), int(set_no), [float(v) for v in values], vertices))
            nodes += nvert
            at += nvert + 2
        if int(fmt.get("No_Fractures", -1)) != len(read) or len(read) != len(discs):
            failures.append(f"{len(read)} fractures, No_Fractures {fmt.get('No_Fractures')}, "
                            f"fractures.csv {len(discs)}")
        if int(fmt.get("No_Nodes", -1)) != nodes:
            failures.append(f"No_Nodes {fmt.get('No_Nodes')}, {nodes} vertex lines")
        for (fid, set_no, values, _), disc in zip(read, discs):
            if fid != int(disc["id"]) or set_names[set_no - 1] != disc["set"]:
                failures.append(f"fracture {fid} set {set_no}: csv {disc['id']} {disc['set']}")
            expected = [float(disc["a"]), float(disc["b"])]
            if values != expected:  # exact: both written in their shortest round-trip form
                failures.append(f"fracture {fid}: values {values}, csv a b {expected}")
        if parts.get("TESSFRACTURE") != []:
            failures.append(f"TESSFRACTURE {parts.get('TESSFRACTURE')}: expected empty")
        if len(set(s for _, s, _, _ in read)) < 3 or len(read) < 10:
            failures.append("too small a check")
        for failure in failures[:20]:
            print(failure)
        print(f"fractures.fab: {len(read)} fractures of sets {set_names}, properties {prop_names}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
