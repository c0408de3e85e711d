# The sliding block of bench/dda_bench.cpp (BM_SlidingAccuracy) in Yade's polyhedra DEM:
# a 1 m rock cube on a fixed 6 x 3 x 1 m slab, gravity tilted 30 deg, friction 20 deg, run to
# t = 0.3 s; its displacement against 1/2 g (sin theta - cos theta tan phi) t^2.
#
#   yade -n -j 1 -x bench/peers/yade_sliding.py [dt_factor ...]
#
# dt = dt_factor x yade_common.time_step(1). No numerical damping (NewtonIntegrator damping
# 0), as the rockmass run (Bossak, rho_inf 0, damps only the contact modes). Each factor runs
# twice: the cube touching the slab (zero overlap) and placed at its static overlap. Prints
# one line per run: dt, steps, signed relative error, CPU seconds (time.process_time).
import math
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(sys.argv[0])))
import yade_common  # noqa: E402

THETA = math.radians(30.0)
PHI = math.radians(20.0)
G = 9.81
END = 0.3


def run(dt_factor, preload):
    O.reset()
    rock = yade_common.rock(PHI)
    O.materials.append(rock)
    O.bodies.append(yade_common.box(rock, (-3, -1.5, -1), (3, 1.5, 0), fixed=True))
    # At its static overlap, m g cos theta / (E A), the cube starts on its contact's rest, as
    # the DDA block starts on its springs; touching, it falls into it and bounces.
    sink = yade_common.DENSITY * G * math.cos(THETA) / yade_common.YOUNG if preload else 0.0
    block = O.bodies.append(yade_common.box(rock, (-2.5, -0.5, -sink), (-1.5, 0.5, 1 - sink)))
    O.engines = yade_common.engines((G * math.sin(THETA), 0, -G * math.cos(THETA)), 0.0)
    O.dt = yade_common.time_step(dt_factor)
    x0 = O.bodies[block].state.pos[0]
    steps = int(math.ceil(END / O.dt))
    start = time.process_time()
    O.run(steps, True)
    cpu = time.process_time() - start
    t = O.time
    a = G * (math.sin(THETA) - math.cos(THETA) * math.tan(PHI))
    expected = 0.5 * a * t * t
    error = ((O.bodies[block].state.pos[0] - x0) - expected) / expected
    print("yade sliding preload %d dt_factor %g dt %.3e steps %d t %.4f signed_rel_error %.4e "
          "cpu_s %.3f" % (preload, dt_factor, O.dt, steps, t, error, cpu), flush=True)


factors = [float(a) for a in sys.argv[1:]] or [1.0, 0.5, 0.2, 0.1]
for preload in (0, 1):
    for f in factors:
        run(f, preload)
