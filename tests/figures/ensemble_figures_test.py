#!/usr/bin/python3
"""The ensemble's figures on a real ensemble: `rockmass ensemble` of a block on a 30 degree
joint whose friction is N(0.65, 0.1) (20 realizations, Latin hypercube) and of horizontal
joints crossed by a borehole; every PNG must be a sensible PNG (figure_smoke_test.check_png)
and say what it shows (its "rockmass" text chunk): the realizations counted, the target and
the probability below it as ensemble.json has them, the input that drives the factor, the
RQD series drawn, and no constant measure in the convergence figure.

Usage: ensemble_figures_test.py ROCKMASS_BINARY. Exits 77 when matplotlib is missing.
"""
import json
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from figure_smoke_test import check_png, description  # noqa: E402

INCLINE = """version: 1
name: incline-ensemble
seed: 3
domain:
  box: {min: [0, 0, -15], max: [20, 10, 0]}
materials:
  rock: {density: 2600, young: 10.0e9, poisson: 0.25}
rock_material: rock
joints:
  plane: {friction: 0.65, cohesion: 0}
default_joint: plane
faults:
  - {name: plane, center: [10, 5, -5.773502691896258], dip_direction: 90, dip: 30}
loads:
  gravity: 9.81
supports:
  fixed: [bottom]
monitors:
  - {name: top, point: [15, 5, -1]}
analysis:
  blocks: {cutter: fast}
  dda: {mode: static, kinematics: rigid, steps: 5, time_step: 0.001}
  equilibrium: {max_steps: 300}
  strength_reduction: {factors: [0.5, 0.7, 0.9, 1.1, 1.3, 1.5, 1.7], tolerance: 0.02}
uncertainty:
  sampling: latin_hypercube
  size: 20
  targets: {strength_reduction: 1.0}
  inputs:
    - {key: joints.plane.friction, distribution: normal, std: 0.1}
"""

HOLES = """version: 1
name: holes-ensemble
seed: 5
domain:
  box: {min: [0, 0, -40], max: [10, 10, 0]}
joint_sets:
  - name: H
    dip_direction: {distribution: constant, mean: 0}
    dip: {distribution: constant, mean: 0}
    spacing: {distribution: exponential, mean: 0.1}
    trace_length: {distribution: constant, mean: 100}
analysis:
  rqd:
    thresholds: [0.1, 0.2, 0.3]
    boreholes: {file: holes.csv, run_length: 40}
"""


def run(binary, d, name, text, count):
    scene = os.path.join(d, name + ".yaml")
    with open(scene, "w") as f:
        f.write(text)
    out = os.path.join(d, name)
    done = subprocess.run([binary, "ensemble", scene, "-o", out, "--realizations", str(count),
                           "--jobs", "2"], capture_output=True, text=True)
    print(done.stderr[-2000:])
    assert done.returncode == 0, f"rockmass ensemble {name} exited with {done.returncode}"
    with open(os.path.join(out, "ensemble.json")) as f:
        return out, json.load(f)


def main():
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        print("matplotlib is not installed: skipped")
        sys.exit(77)
    binary = sys.argv[1]
    with tempfile.TemporaryDirectory() as d:
        out, ensemble = run(binary, d, "incline", INCLINE, 20)
        for png in ("ensemble_factors.png", "ensemble_convergence.png"):
            print(png, check_png(os.path.join(out, png)))
        assert not os.path.exists(os.path.join(out, "ensemble_rqd.png")), "no RQD in this scene"
        info = description(os.path.join(out, "ensemble_factors.png"))
        facts = info["facts"]
        srf = ensemble["stability"]["critical_srf"]
        assert facts["scene"] == "incline-ensemble", facts
        assert facts["realizations"] == 20, facts
        fact = facts["factors"]["critical_srf"]
        assert fact["target"] == 1.0 and fact["probability_below"] == srf["probability_below"]
        assert fact["most_influential"] == "joints.plane.friction", fact
        assert any("P(below)" in e for p in info["panels"] for e in p["legend"]), info["panels"]
        conv = description(os.path.join(out, "ensemble_convergence.png"))
        # The fault's P32 is the same in every realization: not drawn.
        assert conv["facts"]["measures"] == ["critical_srf"], conv["facts"]

        with open(os.path.join(d, "holes.csv"), "w") as f:
            f.write("id,x,y,z,azimuth,plunge,length\nA,5,5,0,0,90,40\n")
        out, ensemble = run(binary, d, "holes", HOLES, 8)
        print("ensemble_rqd.png", check_png(os.path.join(out, "ensemble_rqd.png")))
        rqd = description(os.path.join(out, "ensemble_rqd.png"))
        assert rqd["facts"]["series"] == ["borehole A"], rqd["facts"]
        assert rqd["panels"][0]["ylabel"] == "RQD (%)", rqd["panels"]
        assert not os.path.exists(os.path.join(out, "ensemble_factors.png")), "no factors here"
    print("ensemble figures checked")


if __name__ == "__main__":
    main()
