"""The Python module against the command line: the same numbers as the CLI's files, the CLI's
scene errors as SceneError, a DDA stepped from Python that reproduces `rockmass dda`'s history,
and long calls that release the GIL and stop on Ctrl-C (docs/python.md).

Run by CTest (tests/CMakeLists.txt: python_api) with PYTHONPATH=build/python and
ROCKMASS_BINARY set; `python3 -m pytest tests/python` by hand with the same two.
"""
import csv
import json
import os
import signal
import subprocess
import threading
import time

# rockmass before numpy: its own libblas.so.3 (ATLAS's, docs/dda3d.md "BLAS") is then the
# process's, as in the rockmass program the tests compare with; numpy first would bring the
# system's.
import rockmass  # noqa: I001

import numpy as np
import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
XIANGJIABA = os.path.join(ROOT, "examples", "xiangjiaba", "scene.yaml")
BINARY = os.environ.get("ROCKMASS_BINARY", os.path.join(ROOT, "build", "app", "rockmass"))

with open(os.path.join(ROOT, "tests", "data", "two_sets_small.yaml")) as f:
    SMALL = f.read()  # shared with tests/report


def cli(*args):
    done = subprocess.run([BINARY, *args], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr[-3000:]
    return done


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


@pytest.fixture(scope="module")
def xiangjiaba():
    scene = rockmass.load_scene(XIANGJIABA)
    return scene, rockmass.dfn(scene)


@pytest.fixture()
def small(tmp_path):
    path = tmp_path / "small.yaml"
    path.write_text(SMALL)
    return str(path)


def test_dfn_gives_the_numbers_of_rockmass_dfn(xiangjiaba, tmp_path):
    scene, d = xiangjiaba
    a = d.arrays()
    cli("dfn", XIANGJIABA, "-o", str(tmp_path))
    discs = rows(tmp_path / "fractures.csv")
    assert d.count == len(discs) == len(a["id"])
    assert a["center"].shape == (d.count, 3) and a["semi_axes"].shape == (d.count, 2)
    # fractures.csv writes the shortest text that reads back to the same double: exact.
    centers = np.array([[float(r[k]) for k in ("cx", "cy", "cz")] for r in discs])
    assert np.array_equal(a["center"], centers)
    assert np.array_equal(a["semi_axes"][:, 0], [float(r["a"]) for r in discs])
    names = a["set_names"]
    assert [names[s] for s in a["set"][:1000]] == [r["set"] for r in discs[:1000]]
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert [s["p32"] for s in a["sets"]] == [s["p32"] for s in summary["sets"]]
    assert [s["count"] for s in a["sets"]] == [s["count"] for s in summary["sets"]]
    # The arrays are the module's own buffers handed over (a capsule owns them), not copies.
    assert a["center"].base is not None and not a["center"].flags["OWNDATA"]


def test_rqd_gives_the_numbers_of_rockmass_rqd(xiangjiaba, tmp_path):
    scene, d = xiangjiaba
    r = rockmass.rqd(scene, d)
    cli("rqd", XIANGJIABA, "-o", str(tmp_path), "--no-grid")
    table = rows(tmp_path / "rqd_balls.csv")
    for ball in r["balls"]:
        mine = [row for row in table if row["ball"] == ball["name"]]
        m, t = ball["rqd"].shape
        assert len(mine) == m * t and t == len(ball["thresholds"])
        values = np.array([float(row["rqd"]) for row in mine]).reshape(m, t)
        assert np.array_equal(ball["rqd"], values)
        dirs = np.array([[float(row[k]) for k in ("dir_x", "dir_y", "dir_z")]
                         for row in mine[::t]])
        assert np.array_equal(ball["directions"], dirs)
    summary = json.loads((tmp_path / "summary.json").read_text())
    for hole, expected in zip(r["boreholes"], summary["boreholes"]["holes"]):
        assert hole["id"] == expected["id"]
        assert hole["rqd"] == [e["rqd"] for e in expected["rqd"]]


def test_blocks_give_the_numbers_of_rockmass_blocks(small, tmp_path):
    scene = rockmass.load_scene(small)
    b = rockmass.blocks(scene, rockmass.dfn(scene))
    a = b.arrays()
    cli("blocks", small, "-o", str(tmp_path))
    table = rows(tmp_path / "blocks.csv")
    assert b.count == len(table) == len(a["volume"])
    assert np.array_equal(a["volume"], [float(r["volume"]) for r in table])
    assert np.array_equal(a["centroid"], [[float(r[k]) for k in ("cx", "cy", "cz")]
                                          for r in table])
    assert list(a["pieces"]) == [int(r["pieces"]) for r in table]
    assert [a["material_names"][m] for m in a["material"]] == [r["material"] for r in table]
    # A block's closed surface holds its volume (divergence theorem) and its pieces too.
    vertices, triangles = b.surface(0)
    v0, v1, v2 = (vertices[triangles[:, k]] for k in range(3))
    assert np.einsum("ij,ij->i", v0, np.cross(v1, v2)).sum() / 6 == pytest.approx(
        a["volume"][0], rel=1e-9)
    assert len(b.pieces(0)) == a["pieces"][0]
    with pytest.raises(IndexError):
        b.surface(b.count)


def test_a_bad_scene_raises_scene_error_with_file_line_and_key(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text(SMALL.replace("friction: 0.4", "friction: -0.4"))
    line = 1 + SMALL[:SMALL.index("rj: {friction")].count("\n")
    with pytest.raises(rockmass.SceneError) as error:
        rockmass.load_scene(str(bad))
    assert str(error.value).startswith(f"{bad}:{line}:")
    assert "joints.rj.friction: expected a number >= 0, got -0.4" in str(error.value)
    # The same message as the command line's (after "error: ").
    done = subprocess.run([BINARY, "dfn", str(bad), "-o", str(tmp_path / "o")],
                          capture_output=True, text=True)
    assert done.returncode == 2 and str(error.value) in done.stderr
    # A dict: the key path, and a line of its JSON text.
    with pytest.raises(rockmass.SceneError, match=r"<dict>\.yaml:\d+:\d+: domain"):
        rockmass.scene_from_dict({"version": 1, "domain": {"sphere": 3}})
    scene = rockmass.scene_from_dict({"version": 1, "name": "d",
                                      "domain": {"box": {"min": [0, 0, 0], "max": [1, 1, 1]}}})
    assert scene.name == "d" and not scene.has_dda
    with pytest.raises(rockmass.SceneError, match="no DDA analysis"):
        rockmass.Dda(scene, rockmass.dfn(scene))


def test_step_by_step_dda_reproduces_rockmass_dda(small, tmp_path):
    scene = rockmass.load_scene(small)
    dda = rockmass.Dda(scene, rockmass.dfn(scene))
    samples = {name: [] for name in dda.monitor_names}
    while dda.time < 10 * 0.002 * (1 - 1e-9):
        dda.step()
        for m in dda.monitors():
            samples[m["name"]].append(np.concatenate([m["displacement"], m["velocity"]]))
    cli("dda", small, "-o", str(tmp_path))
    history = rows(tmp_path / "history.csv")
    for name, series in samples.items():
        expected = [[float(r[k]) for k in ("ux", "uy", "uz", "vx", "vy", "vz")]
                    for r in history if r["monitor"] == name][1:]  # t = 0 first
        assert len(expected) == len(series) == 10
        np.testing.assert_allclose(series, expected, rtol=1e-12, atol=1e-15)
    states = dda.blocks()
    assert states["velocity"].shape[1] == 12 and states["fixed"].dtype == bool
    assert np.abs(states["displacement"][~states["fixed"]]).max() > 1e-6  # the loose blocks fell
    assert np.array_equal(states["displacement"][states["fixed"]], 0 * states["displacement"][states["fixed"]])


def test_loads_can_change_between_steps(small):
    scene = rockmass.load_scene(small)
    free = rockmass.Dda(scene, rockmass.dfn(scene))
    weightless = rockmass.Dda(scene, rockmass.dfn(scene))
    weightless.set_gravity([0, 0, 0])
    free.run(10)
    weightless.run(10)
    # Without gravity nothing loads the blocks: they move only by the acceleration the time
    # integration started with (gravity's, at t = 0: a change acts from the next step on),
    # 3e-10 m against the free blocks' 4.8e-6 m, their settling on their contact springs in
    # 0.02 s (none slides yet: one block at its limit starts after 10-30 steps, when depends
    # on the friction tolerance).
    moved = np.abs(free.blocks()["displacement"]).max()
    assert moved > 1e-6
    assert np.abs(weightless.blocks()["displacement"]).max() < 1e-3 * moved
    with pytest.raises(ValueError):
        free.set_gravity([0, 0])
    with pytest.raises(IndexError):
        free.set_point_load(0, [0, 0, 1])  # the scene has no point loads


def test_a_long_call_releases_the_gil_and_stops_on_ctrl_c(tmp_path):
    # The quick Xiangjiaba run takes about 40 s; Ctrl-C after 2 s must end it within seconds
    # (its stages stop at their next safe point) as KeyboardInterrupt, and another Python
    # thread must run while it works.
    scene = rockmass.load_scene(XIANGJIABA)
    ticks = []
    stop = threading.Event()

    def counter():
        while not stop.is_set():
            ticks.append(time.monotonic())
            time.sleep(0.01)

    worker = threading.Thread(target=counter)
    worker.start()
    timer = threading.Timer(2.0, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    start = time.monotonic()
    try:
        with pytest.raises(KeyboardInterrupt):
            rockmass.run(scene, str(tmp_path / "out"), quick=True)
    finally:
        stop.set()
        worker.join()
        timer.cancel()
    elapsed = time.monotonic() - start
    assert 1.5 < elapsed < 15.0, elapsed
    during = [t for t in ticks if start + 0.2 < t < start + elapsed - 0.2]
    assert len(during) > 20, len(during)  # the counter ran while the call worked
    # Python's own Ctrl-C handling is back: the module is usable again.
    assert rockmass.load_scene(XIANGJIABA).name == "xiangjiaba-dam-base"
