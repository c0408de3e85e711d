#!/usr/bin/python3
"""The VTU files rockmass writes, read by two readers this project does not write: meshio
(Debian's python3-meshio) and VTK's own XML reader (python3-vtk9, what ParaView uses):
fractures.vtu, blocks.vtu, faces.vtu, the DDA frames and the damage maps of a small scene.
Each must open without an error or a warning, hold one cell per fracture / piece / face /
piece, and carry its data arrays; the arrays are zlib-compressed as VTK writes them.
(meshio read the polyhedron files as a 2D table and failed while the cells' topology arrays
carried NumberOfComponents="1", which VTK's own writer leaves out.)

Usage: meshio_read_test.py ROCKMASS_BINARY
"""
import csv
import os
import subprocess
import sys
import tempfile

import meshio
import vtk

SCENE = """version: 1
name: meshio-check
seed: 3
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
faults:
  - {name: F1, center: [10, 10, -5], dip_direction: 0, dip: 80}
  - {name: F2, center: [10, 6, -5], dip_direction: 200, dip: 70}
loads:
  gravity: 9.81
supports:
  fixed: [bottom]
analysis:
  blocks: {cutter: fast}
  dda: {mode: static, steps: 4, time_step: 0.01, damage_map: {every: 2}}
"""


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def cells(mesh):
    return sum(len(block.data) for block in mesh.cells)


def main():
    binary = sys.argv[1]
    with tempfile.TemporaryDirectory() as tmp:
        scene = os.path.join(tmp, "scene.yaml")
        with open(scene, "w") as f:
            f.write(SCENE)
        out = os.path.join(tmp, "out")
        subprocess.run([binary, "dda", scene, "-o", out], check=True, capture_output=True)
        subprocess.run([binary, "blocks", scene, "-o", out], check=True, capture_output=True)
        subprocess.run([binary, "dfn", scene, "-o", out], check=True, capture_output=True)
        failures = []

        def check(name, expected_cells, arrays):
            try:
                mesh = meshio.read(os.path.join(out, name))
            except Exception as error:  # meshio raises many kinds
                failures.append(f"{name}: meshio cannot read it: {type(error).__name__}: {error}")
                return
            if expected_cells is not None and cells(mesh) != expected_cells:
                failures.append(f"{name}: {cells(mesh)} cells, expected {expected_cells}")
            for array in arrays:
                if array not in mesh.cell_data:
                    failures.append(f"{name}: no cell array '{array}' ({list(mesh.cell_data)})")

        def vtk_check(name, expected_cells, arrays):
            # VTK reports through its output window: every error or warning it prints while
            # reading the file fails the check.
            messages = vtk.vtkStringOutputWindow()
            vtk.vtkOutputWindow.SetInstance(messages)
            reader = vtk.vtkXMLUnstructuredGridReader()
            reader.SetFileName(os.path.join(out, name))
            reader.Update()
            said = messages.GetOutput().strip()
            if said:
                failures.append(f"{name}: VTK says: {said[:300]}")
            grid = reader.GetOutput()
            if expected_cells is not None and grid.GetNumberOfCells() != expected_cells:
                failures.append(f"{name}: VTK reads {grid.GetNumberOfCells()} cells, "
                                f"expected {expected_cells}")
            data = grid.GetCellData() if arrays[0] != "point:" else grid.GetPointData()
            for array in arrays:
                if array != "point:" and data.GetArray(array) is None:
                    failures.append(f"{name}: VTK finds no array '{array}'")
            return grid

        fractures = rows(os.path.join(out, "fractures.csv"))
        blocks = rows(os.path.join(out, "blocks.csv"))
        pieces = sum(int(b["pieces"]) for b in blocks)
        check("fractures.vtu", len(fractures), ["id", "set"])
        check("blocks.vtu", pieces, ["id", "material", "volume"])
        check("faces.vtu", None, ["block", "joint"])
        frames = sorted(f for f in os.listdir(out) if f.startswith("dda_") and f.endswith(".vtu"))
        if len(frames) < 2:
            failures.append(f"expected DDA frames, found {frames}")
        for frame in frames:
            check(frame, None, ["block", "displacement", "velocity", "stress"])
            # Each frame says what it is: its time, and static_mode = 1 (the scene is
            # static: velocity is reset to 0 every step, which is why it is 0 here).
            mesh = meshio.read(os.path.join(out, frame))
            static = mesh.field_data.get("static_mode")
            if static is None or int(static[0]) != 1 or "TimeValue" not in mesh.field_data:
                failures.append(f"{frame}: field data {mesh.field_data}")
        # The damage maps: one vertex cell per contact that has been closed, with its data.
        maps = sorted(f for f in os.listdir(out) if f.startswith("damage_") and f.endswith(".vtu"))
        damage_rows = rows(os.path.join(out, "damage.csv"))
        if maps != ["damage_000002.vtu", "damage_000004.vtu"]:
            failures.append(f"expected the damage maps of steps 2 and 4, found {maps}")
        for name in maps:
            try:
                mesh = meshio.read(os.path.join(out, name))
            except Exception as error:  # meshio raises many kinds
                failures.append(f"{name}: meshio cannot read it: {type(error).__name__}: {error}")
                continue
            if name == maps[-1] and (cells(mesh) != len(damage_rows) or not damage_rows):
                failures.append(f"{name}: {cells(mesh)} points, damage.csv {len(damage_rows)}")
            for array in ("state", "damage", "opening", "slip", "normal_force", "normal"):
                if array not in mesh.point_data:
                    failures.append(f"{name}: no point array '{array}' ({list(mesh.point_data)})")
        vtk_check("fractures.vtu", len(fractures), ["id", "set"])
        grid = vtk_check("blocks.vtu", pieces, ["id", "material", "volume", "piece_volume"])
        # The pieces share their welded points: the grid's bounds, as VTK computes them from
        # the points, are the blocks' bounds in blocks.csv.
        bounds = grid.GetBounds()
        low = [min(float(b[k]) for b in blocks) for k in ("xmin", "ymin", "zmin")]
        high = [max(float(b[k]) for b in blocks) for k in ("xmax", "ymax", "zmax")]
        for axis in range(3):
            if abs(bounds[2 * axis] - low[axis]) > 1e-9 or abs(bounds[2 * axis + 1] - high[axis]) > 1e-9:
                failures.append(f"blocks.vtu: VTK bounds {bounds}, blocks.csv {low} {high}")
                break
        vtk_check("faces.vtu", None, ["block", "joint"])
        for frame in frames:
            vtk_check(frame, None, ["block", "displacement", "velocity", "stress"])
        for name in maps:
            vtk_check(name, None, ["point:", "state", "damage", "opening", "slip"])
        # The data stay with their cells: each block's pieces add up to its volume.
        mesh = meshio.read(os.path.join(out, "blocks.vtu"))
        ids = [int(x) for part in mesh.cell_data["id"] for x in part]
        volumes = [float(x) for part in mesh.cell_data["piece_volume"] for x in part]
        total = {}
        for block, volume in zip(ids, volumes):
            total[block] = total.get(block, 0.0) + volume
        for b in blocks:
            expected = float(b["volume"])
            got = total.get(int(b["id"]), 0.0)
            if abs(got - expected) > 1e-9 * max(1.0, expected):
                failures.append(f"blocks.vtu: block {b['id']}: pieces {got} m3, blocks.csv {expected}")
        if len(blocks) < 3 or len(fractures) < 3:
            failures.append(f"too small a check: {len(blocks)} blocks, {len(fractures)} fractures")
        for failure in failures:
            print(failure)
        print(f"meshio and VTK read {3 + len(frames) + len(maps)} files: {len(fractures)} fractures, "
              f"{len(blocks)} blocks ({pieces} pieces), {len(frames)} frames")
        return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
