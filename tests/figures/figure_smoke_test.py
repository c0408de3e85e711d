#!/usr/bin/python3
"""Test of one figure script: runs it on a tiny generated input and checks that the PNG
exists, is a valid PNG (signature, IHDR chunk with its CRC, IEND at the end) of a sensible
size (at least 200 x 200 pixels, more than 5 kB: a figure with content, not an empty
canvas), and that what it shows is what it says: the description every script stores in
the PNG's text chunk "rockmass" (figure_io.describe: titles, axis labels, legends, texts and
the script's facts) is checked figure by figure (CHECKS: the fitted population, units, the
plane named, the compass marks, the thresholds chosen, the measured logs).

Usage: figure_smoke_test.py SCRIPTS_DIR NAME   (NAME: a script of scripts/figures without .py,
or make_figures). Exits 77 (CTest SKIP_RETURN_CODE) when matplotlib is missing.
"""
import json
import math
import os
import struct
import subprocess
import sys
import tempfile
import zlib

try:
    import matplotlib  # noqa: F401
except ImportError:
    print("matplotlib is not installed: skipped")
    sys.exit(77)


def write(path, header, rows):
    with open(path, "w") as f:
        f.write(header + "\n")
        for row in rows:
            f.write(",".join(str(x) for x in row) + "\n")


def fibonacci(n):
    """n unit vectors spread over the sphere."""
    out = []
    for i in range(n):
        z = 1 - 2 * (i + 0.5) / n
        r = math.sqrt(1 - z * z)
        phi = i * math.pi * (3 - math.sqrt(5))
        out.append((r * math.cos(phi), r * math.sin(phi), z))
    return out


def make_inputs(d):
    """Tiny versions of every rockmass output the scripts read."""
    write(os.path.join(d, "fractures.csv"),
          "id,set,cx,cy,cz,dip_direction,dip,a,b,major_x,major_y,major_z",
          [(i + 1, "J1" if i % 2 else "J2", 0, 0, 0, (37 * i) % 360, 20 + (13 * i) % 60, 1, 1,
            1, 0, 0) for i in range(60)])
    # Two sets of 30 discs and a fault of 2 (too few for density contours).
    with open(os.path.join(d, "fractures.csv"), "a") as f:
        f.write("61,F1,0,0,0,120,70,5,5,1,0,0\n62,F1,1,0,0,122,72,5,5,1,0,0\n")
    balls = []
    for ball in ("heel", "toe"):
        for (x, y, z) in fibonacci(60):
            # t = 0.01 (every direction about 100 %) and 8 m (all 0) are flat maps.
            for t in (0.01, 0.1, 1, 3, 5, 8):
                balls.append((ball, x, y, z, t, max(0.0, 100 - t * (15 + 10 * abs(z)))))
    write(os.path.join(d, "rqd_balls.csv"), "ball,dir_x,dir_y,dir_z,threshold,rqd", balls)
    write(os.path.join(d, "boreholes.csv"), "borehole,from,to,threshold,rqd",
          [(h, 3 * k, 3 * k + 3, t, max(0, 95 - 12 * t - k)) for h in ("ZK1", "ZK2")
           for k in range(4) for t in (0.1, 1, 3, 5)])
    # 200 rock blocks and a dam (a structure: not part of the rock's distribution).
    write(os.path.join(d, "blocks.csv"), "id,volume,cx,cy,cz,material,pieces,structure",
          [(i + 1, 5.0 * (1 + (i * 7919) % 97) ** 1.3, 0, 0, 0, "rock", 1, "")
           for i in range(200)] + [(201, 2.0e5, 0, 0, 50, "concrete", 1, "dam")])
    write(os.path.join(d, "measured.csv"), "id,from,to,rqd", [("ZK1", 0, 6, 80), ("ZK1", 6, 12, 60)])
    with open(os.path.join(d, "summary.json"), "w") as f:
        # The overload's bracket and runs (at rest, not at rest, failing) for the curve; the
        # rock's fit and the whole model's (which the figure must not draw); a measured log.
        json.dump({"name": "smoke-scene", "weibull": {"shape": 0.3, "scale": 1.0},
                   "rock": {"weibull": {"shape": 0.9, "scale": 150.0}},
                   "boreholes": {"measured": {"file": "measured.csv", "threshold": 0.1}},
                   "safety_factor": 3.5,
                   "overload": {"last_stable": 3, "first_unstable": 4, "runs": [
                       {"factor": k, "at_rest": k <= 3, "failing": k == 5}
                       for k in (1, 2, 3, 4, 5)]}}, f)
    write(os.path.join(d, "history.csv"), "time,monitor,ux,uy,uz,vx,vy,vz,u",
          [(0.01 * s, m, 0.001 * s * (i + 1), 0, -0.0005 * s, 0.1, 0, -0.05, 0.001 * s)
           for s in range(50) for i, m in enumerate(("P1", "P2"))])
    # A static run: velocities reset every step, all zero in the file (the figure then shows
    # the rate of each step's displacement).
    write(os.path.join(d, "history_static.csv"), "time,monitor,ux,uy,uz,vx,vy,vz,u",
          [(0.002 * s, m, 1e-6 * (1 - 0.8 ** s) * (i + 1), 0, -2e-6 * (1 - 0.7 ** s), 0, 0, 0,
            1e-6) for s in range(40) for i, m in enumerate(("P1", "D1"))])
    write(os.path.join(d, "overload.csv"), "factor,monitor,ux,uy,uz,u",
          [(k, m, 0.01 * k ** 2 * (i + 1), 0, -0.002 * k, 0.01 * k ** 2)
           for k in (1, 2, 3, 4, 5) for i, m in enumerate(("P1", "P2"))])
    rows = [("block", 1, "rock", 0, v, u, w, u, 1, w, src) for v, (u, w, src) in
            enumerate([(0, -3, "boundary:4"), (2, -3, "boundary:1"), (2, -1, "disc:1"),
                       (0, -1, "boundary:0")])]
    rows += [("block", 2, "concrete", 0, v, u, w, u, 1, w, src) for v, (u, w, src) in
             enumerate([(0, -1, "disc:1"), (2, -1, "fictitious"), (1, 0, "boundary:5")])]
    rows += [("joint", 3, "J1", 0, 0, 0.2, -2.5, 0.2, 1, -2.5, "cutting"),
             ("joint", 3, "J1", 0, 1, 1.5, -1.2, 1.5, 1, -1.2, "cutting"),
             ("fault", 1, "F1", 0, 0, 0, -1, 0, 1, -1, "cutting"),
             ("fault", 1, "F1", 0, 1, 2, -1, 2, 1, -1, "cutting"),
             ("interlayer", 4, "P1", 0, 0, 0, -2, 0, 1, -2, "cutting"),
             ("interlayer", 4, "P1", 0, 1, 2, -2.2, 2, 1, -2.2, "cutting")]
    write(os.path.join(d, "section.csv"), "kind,id,label,part,vertex,u,v,x,y,z,source", rows)
    # The last damage map of a run: contacts of every class, some off the section's slab.
    classes = [("locked", "intact"), ("locked", "bond_broken"), ("sliding", "sliding"),
               ("open", "opened")]
    write(os.path.join(d, "damage.csv"),
          "step,time,x,y,z,nx,ny,nz,block_i,block_j,joint,state,damage,opening,slip,normal_force",
          [(100, 1.0, 0.05 * i, 1 + (i % 7) * 0.4, -3 + 0.02 * i, 0, 0, 1, 1, 2, 0,
            *classes[i % 4], 1e-4 * (i % 4 == 3), 2e-4 * (i % 4 == 2), 1e5)
           for i in range(120)])


COMMANDS = {
    "stereonet": lambda d: ["fractures.csv"],
    "rqd_threshold": lambda d: ["--balls", "rqd_balls.csv", "--boreholes", "boreholes.csv",
                                "--summary", "summary.json"],
    "rqd_ball_maps": lambda d: ["rqd_balls.csv"],
    "block_volumes": lambda d: ["blocks.csv", "--summary", "summary.json"],
    "histories": lambda d: ["history.csv"],
    "overload_curve": lambda d: ["overload.csv", "--summary", "summary.json"],
    "section": lambda d: ["section.csv"],
    "damage_map": lambda d: ["damage.csv", "--section", "section.csv", "--plane", "y=1"],
}


def check_png(path):
    """Fails unless `path` is a well-formed PNG of a sensible size."""
    with open(path, "rb") as f:
        data = f.read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", f"{path}: not a PNG signature"
    length, kind = struct.unpack(">I4s", data[8:16])
    assert kind == b"IHDR" and length == 13, f"{path}: first chunk is not IHDR"
    body = data[16:29]
    crc, = struct.unpack(">I", data[29:33])
    assert zlib.crc32(b"IHDR" + body) == crc, f"{path}: IHDR CRC mismatch"
    width, height = struct.unpack(">II", body[:8])
    assert width >= 200 and height >= 200, f"{path}: {width} x {height} pixels is too small"
    assert data[-12:] == b"\x00\x00\x00\x00IEND\xaeB`\x82", f"{path}: no IEND chunk at the end"
    assert len(data) > 5000, f"{path}: {len(data)} bytes is an empty canvas"
    return width, height, len(data)


def description(path):
    """The JSON of the PNG's text chunk "rockmass" (figure_io.describe)."""
    with open(path, "rb") as f:
        data = f.read()
    at = 8
    while at < len(data):
        length, kind = struct.unpack(">I4s", data[at:at + 8])
        body = data[at + 8:at + 8 + length]
        if kind == b"tEXt" and body.startswith(b"rockmass\0"):
            return json.loads(body[9:].decode("latin-1"))
        at += 12 + length
    raise AssertionError(f"{path}: no 'rockmass' text chunk")


def check_block_volumes(info):
    facts = info["facts"]
    # The rock's 200 blocks, not the dam; the rock's own fit (rock.weibull).
    assert facts["population"] == "rock blocks" and facts["blocks"] == 200, facts
    assert facts["structure_blocks"] == 1 and facts["fit"] == "rock.weibull", facts
    assert facts["bins"] == "log10", facts
    assert any("k = 0.9" in entry for entry in info["panels"][0]["legend"]), info["panels"][0]
    assert all("m³" in p["xlabel"] for p in info["panels"]), info["panels"]


def check_overload_curve(info):
    units = {p["ylabel"].rsplit("(", 1)[1] for p in info["panels"]}
    assert len(units) == 1, f"panels in different units: {units}"
    assert info["facts"]["joined"] == "runs at rest only", info["facts"]
    # K_s = 3.5, the middle of the bracket [3, 4]: its half-width is said.
    assert any("K_s = 3.5 ± 0.5" in e for e in info["panels"][0]["legend"]), info["panels"][0]


def check_section(info):
    assert info["facts"]["plane"] == "y = 1 m", info["facts"]
    assert "y = 1 m" in info["suptitle"], info["suptitle"]
    for panel in info["panels"]:
        assert (panel["xlabel"], panel["ylabel"]) == ("x (m)", "z (m)"), panel
    assert len(info["panels"]) == 2 and "enlarged" in info["panels"][1]["title"], info["panels"]


def check_stereonet(info):
    sets = info["facts"]["sets"]
    assert sets["F1"]["contoured"] is False and sets["J1"]["contoured"] is True, sets
    assert sets["J1"]["kappa"] is not None and sets["J1"]["kappa"] > 0, sets
    # The fault's two planes 120/70 and 122/72: the mean plane between them.
    assert abs(sets["F1"]["mean_dip_direction"] - 121) < 1.5, sets["F1"]
    assert abs(sets["F1"]["mean_dip"] - 71) < 1.5, sets["F1"]
    for panel in info["panels"]:
        if "discs" in panel["title"]:
            assert {"N", "E", "S", "W"} <= set(panel["texts"]), panel
            assert "mean plane" in panel["title"] and "κ" in panel["title"], panel


def check_rqd_ball_maps(info):
    # The flat maps (t = 0.01 m, every direction near 100 %; t = 8 m, all 0) are left out.
    assert info["facts"]["thresholds"] == [0.1, 1, 3, 5], info["facts"]


def check_rqd_threshold(info):
    assert info["facts"]["measured"] == ["ZK1"], info["facts"]
    assert any("measured" in e for p in info["panels"] for e in p["legend"]), info["panels"]


CHECKS = {"block_volumes": check_block_volumes, "overload_curve": check_overload_curve,
          "section": check_section, "stereonet": check_stereonet,
          "rqd_ball_maps": check_rqd_ball_maps, "rqd_threshold": check_rqd_threshold}


def main():
    scripts, name = os.path.abspath(sys.argv[1]), sys.argv[2]
    with tempfile.TemporaryDirectory() as d:
        make_inputs(d)
        if name == "make_figures":
            done = subprocess.run([sys.executable, os.path.join(scripts, "make_figures.py"), d],
                                  capture_output=True, text=True)
            print(done.stdout, done.stderr)
            assert done.returncode == 0, "make_figures.py failed"
            reported = [line[8:] for line in done.stdout.splitlines()
                        if line.startswith("figure: ")]
            assert len(reported) == len(COMMANDS), f"expected {len(COMMANDS)} figures: {reported}"
            # make_figures.FIGURES (the names --only and --skip accept) lists every figure it
            # draws: one left out of it could not be drawn early or skipped.
            sys.path.insert(0, scripts)
            import make_figures
            assert set(reported) <= set(make_figures.FIGURES), (reported, make_figures.FIGURES)
            for png in reported:
                print(png, check_png(os.path.join(d, png)))
                # Every figure names the scene it is of, in its title.
                info = description(os.path.join(d, png))
                assert info["facts"].get("scene") == "smoke-scene", (png, info["facts"])
                assert info["suptitle"].startswith("smoke-scene"), (png, info["suptitle"])
            # `rockmass run` draws two figures early (--only, the scene's name given, as
            # summary.json is not written yet) and the others at the end (--skip): together
            # the same figures.
            early = "stereonet.png,section.png"
            parts = []
            for arguments in (["--only", early, "--scene", "early-scene"], ["--skip", early]):
                done = subprocess.run([sys.executable, os.path.join(scripts, "make_figures.py"), d,
                                       *arguments], capture_output=True, text=True)
                assert done.returncode == 0, done.stdout + done.stderr
                parts.append([line[8:] for line in done.stdout.splitlines()
                              if line.startswith("figure: ")])
            assert sorted(parts[0]) == ["section.png", "stereonet.png"], parts[0]
            assert sorted(parts[0] + parts[1]) == sorted(reported), parts
            info = description(os.path.join(d, "stereonet.png"))
            assert info["facts"].get("scene") == "early-scene", info["facts"]
            # A misspelt name is refused (it would leave a figure out without a word).
            done = subprocess.run([sys.executable, os.path.join(scripts, "make_figures.py"), d,
                                   "--skip", "stereonet.pn"], capture_output=True, text=True)
            assert done.returncode == 2 and "unknown figure stereonet.pn" in done.stderr, done
            return
        out = os.path.join(d, name + ".png")
        done = subprocess.run([sys.executable, os.path.join(scripts, name + ".py"),
                               *COMMANDS[name](d), "-o", out], capture_output=True, text=True,
                              cwd=d)
        print(done.stdout, done.stderr)
        assert done.returncode == 0, f"{name}.py exited with {done.returncode}"
        print(name, check_png(out))
        if name in CHECKS:
            CHECKS[name](description(out))
            print(name, "description checked")
        if name == "histories":
            out = os.path.join(d, "histories_static.png")
            done = subprocess.run([sys.executable, os.path.join(scripts, "histories.py"),
                                   "history_static.csv", "-o", out], capture_output=True,
                                  text=True, cwd=d)
            print(done.stdout, done.stderr)
            assert done.returncode == 0, f"histories.py (static) exited with {done.returncode}"
            print("histories (static)", check_png(out))


if __name__ == "__main__":
    main()
