#!/usr/bin/python3
"""blocks.glb of a small two-material scene, checked by a validator this project does not
write (Khronos' glTF-Validator, npm gltf-validator, run with Node.js: no error and no
warning) and read back from the glb's own JSON chunk (the glTF 2.0 specification, "Binary
glTF Layout"): the root node turns the model's z up into glTF's y up (a quarter turn about
x), and there is one node per block of blocks.csv, named block_<id>, whose extras carry the
block's id, volume and material as blocks.csv gives them.

Usage: glb_check.py ROCKMASS_BINARY VALIDATOR_SCRIPT VALIDATOR_MODULE_DIR
"""
import csv
import json
import math
import os
import struct
import subprocess
import sys
import tempfile

SCENE = """version: 1
name: glb-check
seed: 5
domain:
  box: {min: [0, 0, -10], max: [20, 20, 0]}
materials:
  rock: {density: 2650, young: 7.0e9, poisson: 0.25}
  soft: {density: 2000, young: 1.0e9, poisson: 0.35}
rock_material: rock
joints:
  rj: {friction: 0.86, cohesion: 0}
default_joint: rj
joint_sets:
  - name: J1
    orientation: {distribution: fisher, dip_direction: 90, dip: 60, kappa: 50}
    spacing: {distribution: lognormal, mean: 3.0, std: 1.0}
    trace_length: {distribution: lognormal, mean: 15.0, std: 5.0}
interlayers:
  - {name: L1, material: soft, thickness: 1.0, sweep: y, profile: [[0, -5], [20, -6]]}
analysis:
  blocks: {cutter: fast}
"""


def glb_json(path):
    with open(path, "rb") as f:
        data = f.read()
    magic, version, length = struct.unpack_from("<4sII", data, 0)
    if magic != b"glTF" or version != 2 or length != len(data):
        raise ValueError(f"not a glb 2.0 file: {magic} {version} {length} / {len(data)}")
    chunk_length, chunk_type = struct.unpack_from("<II", data, 12)
    if chunk_type != 0x4E4F534A:  # "JSON"
        raise ValueError("the first chunk is not JSON")
    return json.loads(data[20:20 + chunk_length].decode("utf-8"))


def main():
    binary, script, module = sys.argv[1:4]
    if not os.path.isdir(module):
        print(f"the glTF validator is not installed ({module}); bash scripts/setup-debian.sh "
              "installs it with npm")
        return 1
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        scene = os.path.join(tmp, "scene.yaml")
        with open(scene, "w") as f:
            f.write(SCENE)
        out = os.path.join(tmp, "out")
        subprocess.run([binary, "blocks", scene, "-o", out, "--mesh-format", "glb"], check=True,
                       capture_output=True)
        glb = os.path.join(out, "blocks.glb")
        validated = subprocess.run(["node", script, module, glb], capture_output=True, text=True)
        print(validated.stdout.strip())
        if validated.returncode != 0:
            failures.append(f"the glTF validator rejects blocks.glb: {validated.stdout} "
                            f"{validated.stderr}")
        with open(os.path.join(out, "blocks.csv"), newline="") as f:
            blocks = list(csv.DictReader(f))
        gltf = glb_json(glb)
        root = gltf["nodes"][gltf["scenes"][gltf.get("scene", 0)]["nodes"][0]]
        half = math.sqrt(0.5)
        rotation = root.get("rotation", [0, 0, 0, 1])
        if any(abs(a - b) > 1e-12 for a, b in zip(rotation, [-half, 0, 0, half])):
            failures.append(f"root rotation {rotation}: expected a quarter turn about x")
        children = [gltf["nodes"][c] for c in root.get("children", [])]
        if len(children) != len(blocks):
            failures.append(f"{len(children)} block nodes, blocks.csv {len(blocks)} blocks")
        materials = {b["material"] for b in blocks}
        if len(materials) < 2:
            failures.append(f"too small a check: materials {materials}")
        for node, block in zip(children, blocks):
            extras = node.get("extras", {})
            if node.get("name") != "block_" + block["id"] or extras.get("id") != int(block["id"]):
                failures.append(f"node {node.get('name')} {extras}: expected block {block['id']}")
                continue
            volume = float(block["volume"])
            if abs(extras.get("volume", -1.0) - volume) > 1e-12 * max(1.0, volume):
                failures.append(f"block {block['id']}: volume {extras.get('volume')}, csv {volume}")
            if extras.get("material") != block["material"]:
                failures.append(f"block {block['id']}: material {extras.get('material')}, "
                                f"csv {block['material']}")
            material = gltf["materials"][gltf["meshes"][node["mesh"]]["primitives"][0]["material"]]
            if material.get("name") != block["material"]:
                failures.append(f"block {block['id']}: glTF material {material.get('name')}")
        for failure in failures[:20]:
            print(failure)
        print(f"blocks.glb: {len(children)} block nodes, materials {sorted(materials)}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
