# The settling pile of bench/dda_bench.cpp (BM_PileSettling/.../1000) in Yade's polyhedra DEM:
# 1 000 rock cubes of 1 m in staggered layers 2 cm apart, the lowest 0.05 m above a fixed
# slab, released under gravity; CPU time for 0.3 s of model time.
#
#   yade -n -j 1 -x bench/peers/yade_pile.py [dt_factor] [damping] [gap]
#
# dt = dt_factor x yade_common.time_step(1) (default 0.5); damping is NewtonIntegrator's
# non-viscous damping (default 0: none but the contact law's own); gap in m (default 0.02).
# Prints the steps, the CPU seconds (time.process_time) and the contacts at the end.
import math
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(sys.argv[0])))
import yade_common  # noqa: E402

BLOCKS = 1000
END = 0.3
dt_factor = float(sys.argv[1]) if len(sys.argv) > 1 else 0.5
damping = float(sys.argv[2]) if len(sys.argv) > 2 else 0.0
gap = float(sys.argv[3]) if len(sys.argv) > 3 else 0.02

rock = yade_common.rock(math.radians(30.0))
O.materials.append(rock)
side = int(math.ceil(math.sqrt(BLOCKS / 8.0)))
pitch = 1.0 + gap
width = pitch * side + 0.6
O.bodies.append(yade_common.box(rock, (-1, -1, -1), (width + 1, width + 1, 0), fixed=True))
for k in range(BLOCKS):
    per_layer = side * side
    layer, row, column = k // per_layer, (k // side) % side, k % side
    shift = 0.0 if layer % 2 == 0 else 0.3
    low = (0.1 + pitch * column + shift, 0.1 + pitch * row, 0.05 + pitch * layer)
    O.bodies.append(yade_common.box(rock, low, (low[0] + 1, low[1] + 1, low[2] + 1)))
O.engines = yade_common.engines((0, 0, -9.81), damping)
O.dt = yade_common.time_step(dt_factor)
steps = int(math.ceil(END / O.dt))
start = time.process_time()
O.run(steps, True)
cpu = time.process_time() - start
real = sum(1 for i in O.interactions if i.isReal)
print("yade pile blocks %d dt %.3e steps %d t %.4f cpu_s %.2f contacts %d" %
      (BLOCKS, O.dt, steps, O.time, cpu, real), flush=True)
