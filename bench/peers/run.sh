#!/usr/bin/env bash
# rockmass and Yade (Debian's `yade`, polyhedra DEM) on the same two problems, one core each:
#  1. a 1 m cube sliding on a 30 deg slab, friction 20 deg, to 0.3 s: error against
#     1/2 g (sin theta - cos theta tan phi) t^2 and CPU time, for several time steps;
#  2. 1 000 cubes in staggered layers 2 cm apart released onto a slab: CPU time for 0.3 s.
# Run after building (bash scripts/test.sh or cmake --build build); any working directory;
# needs `apt-get install yade`. Results and the differences between the codes:
# docs/performance.md, "Side by side with Yade". About 4 minutes.
set -euo pipefail
cd "$(dirname "$0")/../.."
command -v yade >/dev/null || { echo "yade is not installed (apt-get install yade)" >&2; exit 2; }
bench=build/bench/dda_bench
[ -x "$bench" ] || { echo "$bench is missing: build first" >&2; exit 2; }
cpu=0  # one core for both codes

echo "== sliding block, rockmass (BM_SlidingAccuracy: dt in ms/4, penalty factor, solver)"
taskset -c "$cpu" "$bench" --benchmark_filter='BM_SlidingAccuracy' --benchmark_counters_tabular=true 2>/dev/null |
  grep -E 'BM_Sliding|rel_error'
echo "== sliding block, Yade"
taskset -c "$cpu" yade -n -j 1 -x bench/peers/yade_sliding.py 1 0.5 0.2 0.1 2>/dev/null | grep '^yade sliding'

echo "== settling pile of 1000 cubes to 0.3 s, rockmass (CPU seconds of the whole program)"
/usr/bin/time -f 'rockmass pile cpu_s %U user %S sys, %e s wall' \
  taskset -c "$cpu" "$bench" --benchmark_filter='BM_PileSettling' --dda_solvers=cholmod 2>&1 |
  grep -E 'steps/s|rockmass pile|cholmod +1000'
echo "== settling pile of 1000 cubes to 0.3 s, Yade"
taskset -c "$cpu" yade -n -j 1 -x bench/peers/yade_pile.py 0.5 0 0.02 2>/dev/null | grep '^yade pile'
