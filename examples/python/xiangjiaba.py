#!/usr/bin/python3
"""The Xiangjiaba scene from Python (docs/python.md): the fracture network, an RQD ball, the
blocks, the overload method on the quick box, and a DDA stepped with a load changed halfway.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/xiangjiaba.py [OUTDIR]

Writes xiangjiaba_rqd_ball.png, xiangjiaba_overload.png and xiangjiaba_steps.png into OUTDIR
(default out/python); the overload takes about 40 s on 2 cores.
"""
import os
import sys

# rockmass first: the process then runs CHOLMOD on rockmass's own BLAS (ATLAS; numpy
# imported first would bring the system's: docs/dda3d.md, "BLAS").
import rockmass  # noqa: I001

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

here = os.path.dirname(os.path.abspath(__file__))
out = sys.argv[1] if len(sys.argv) > 1 else "out/python"
os.makedirs(out, exist_ok=True)

scene = rockmass.load_scene(os.path.join(here, "..", "xiangjiaba", "scene.yaml"))
network = rockmass.dfn(scene)
discs = network.arrays()
print(f"{scene.name}: {network.count} discs")
for s in discs["sets"]:
    print(f"  {s['name']:6s} {s['count']:7d} discs, P32 {s['p32']:.3f} m2/m3")

# The RQD ball under the dam's centre: RQD against the direction's plunge, per threshold.
rqd = rockmass.rqd(scene, network)
ball = next(b for b in rqd["balls"] if b["name"] == "centre")
plunge = np.degrees(np.arcsin(-ball["directions"][:, 2]))
fig, ax = plt.subplots(figsize=(7, 4.5))
for k, t in enumerate(ball["thresholds"]):
    if t in (0.1, 1.0, 2.0, 4.0):
        ax.plot(plunge, ball["rqd"][:, k], ".", ms=2, label=f"t = {t:g} m")
ax.set_xlabel("plunge of the scanline (deg, down > 0)")
ax.set_ylabel("RQD (%)")
ax.set_title(f"{scene.name}: RQD ball '{ball['name']}', {len(plunge)} directions")
ax.legend(markerscale=5)
fig.savefig(os.path.join(out, "xiangjiaba_rqd_ball.png"), dpi=120)

# The overload method on the quick box (the dam's footprint, the top sixth of the depth).
summary = rockmass.overload(scene, os.path.join(out, "overload"), quick=True)
runs = summary["overload"]["runs"]
fig, ax = plt.subplots(figsize=(6, 4))
factors = [r["factor"] for r in runs]
ax.plot(factors, [r["unbalanced_ratio"] for r in runs], "o-")
ax.set_yscale("log")
ax.axhline(summary["equilibrium"]["unbalanced_ratio"], color="grey", ls="--", label="at rest below")
ax.set_xlabel("overload factor K")
ax.set_ylabel("unbalanced ratio at the end of the run")
ax.set_title(f"K_s = {summary['overload']['K_s']}")
ax.legend()
fig.savefig(os.path.join(out, "xiangjiaba_overload.png"), dpi=120)
print("K_s on the quick box:", summary["overload"]["K_s"])

# A DDA stepped from Python on a small scene of the same kind: gravity doubled after 10 steps.
small = rockmass.scene_from_dict({
    "version": 1, "name": "two-joint-sets", "seed": 42,
    "domain": {"box": {"min": [0, 0, -6], "max": [6, 6, 0]}},
    "materials": {"rock": {"density": 2600, "young": 10e9, "poisson": 0.25}},
    "rock_material": "rock",
    "joints": {"rj": {"friction": 0.4, "cohesion": 0}}, "default_joint": "rj",
    "joint_sets": [
        {"name": "S1", "dip_direction": {"distribution": "normal", "mean": 90, "std": 10},
         "dip": {"distribution": "normal", "mean": 45, "std": 8},
         "spacing": {"distribution": "exponential", "mean": 2.0},
         "trace_length": {"distribution": "lognormal", "mean": 8, "std": 2}},
        {"name": "S2", "dip_direction": {"distribution": "normal", "mean": 200, "std": 10},
         "dip": {"distribution": "normal", "mean": 70, "std": 8},
         "spacing": {"distribution": "exponential", "mean": 2.5},
         "trace_length": {"distribution": "lognormal", "mean": 8, "std": 2}}],
    "loads": {"gravity": 9.81}, "supports": {"fixed": ["bottom"]},
    "analysis": {"blocks": {"cutter": "fast"},
                 "dda": {"mode": "dynamic", "kinematics": "rigid", "steps": 20,
                         "time_step": 0.002}}})
dda = rockmass.Dda(small, rockmass.dfn(small))
t, uz = [], []
for step in range(20):
    if step == 10:
        dda.set_gravity([0, 0, -2 * 9.81])
    dda.step()
    t.append(dda.time)
    states = dda.blocks()
    uz.append(states["displacement"][~states["fixed"], 2].min())  # the block that fell most
fig, ax = plt.subplots(figsize=(6, 4))
ax.plot(t, 1000 * np.array(uz), "o-")
ax.axvline(t[9], color="grey", ls="--", label="gravity doubled")
ax.set_xlabel("t (s)")
ax.set_ylabel("largest fall of a loose block, uz (mm)")
ax.legend()
fig.savefig(os.path.join(out, "xiangjiaba_steps.png"), dpi=120)
print("figures in", out)
