#!/bin/bash
# Throughput of rockmass ensemble on the Xiangjiaba scene (docs/performance.md, "Ensembles"):
# realizations per hour of the DFN + RQD stages (--stages rqd) and of the quick stability run
# (--quick), on 1 and 2 local processes and on 2 MPI ranks, with the ratios measured in the
# same run, and the peak memory of one realization (the memory of a rank: a rank runs one
# realization at a time).
#
#   bash bench/ensemble_bench.sh [RQD_REALIZATIONS=8] [QUICK_REALIZATIONS=4]
set -euo pipefail
cd "$(dirname "$0")/.."
binary=build/app/rockmass
scene=examples/xiangjiaba/scene.yaml
rqd_n=${1:-8}
quick_n=${2:-4}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

seconds() {  # seconds of a command, its output discarded
  local start end
  start=$(date +%s.%N)
  "$@" > /dev/null 2>&1
  end=$(date +%s.%N)
  echo "$end - $start" | bc
}
per_hour() { echo "scale=1; 3600 * $1 / $2" | bc; }
peak_mb() {  # peak resident memory of a command (MB)
  /usr/bin/time -f %M "$@" 2>&1 > /dev/null | tail -1 | awk '{printf "%.0f", $1 / 1024}'
}

echo "machine: $(nproc) cores; $(git describe --always 2>/dev/null || echo unknown)"
for case in "rqd:--stages rqd:$rqd_n" "quick:--quick:$quick_n"; do
  IFS=: read -r name options n <<< "$case"
  # shellcheck disable=SC2086
  one=$(seconds $binary ensemble $scene -o "$work/$name-1" --realizations "$n" $options --no-figures --jobs 1)
  # shellcheck disable=SC2086
  two=$(seconds $binary ensemble $scene -o "$work/$name-2" --realizations "$n" $options --no-figures --jobs 2)
  mpi="(no mpirun)"
  if command -v mpirun > /dev/null && $binary --version | grep -q '^  MPI '; then
    # shellcheck disable=SC2086
    mpi=$(OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 seconds mpirun -n 2 \
      --oversubscribe $binary ensemble $scene -o "$work/$name-mpi" --realizations "$n" \
      $options --no-figures --threads 1)
  fi
  # shellcheck disable=SC2086
  memory=$(peak_mb $binary ensemble $scene -o "$work/$name-m" --realizations "$n" $options \
    --no-figures --only 0)
  printf '%-6s %2d realizations: 1 process %6.1f s (%s /h), 2 processes %6.1f s (%s /h, x%s), ' \
    "$name" "$n" "$one" "$(per_hour "$n" "$one")" "$two" "$(per_hour "$n" "$two")" \
    "$(echo "scale=2; $one / $two" | bc)"
  if [ "$mpi" = "(no mpirun)" ]; then
    printf '2 MPI ranks %s, ' "$mpi"
  else
    printf '2 MPI ranks %6.1f s (%s /h, x%s), ' "$mpi" "$(per_hour "$n" "$mpi")" \
      "$(echo "scale=2; $one / $mpi" | bc)"
  fi
  printf 'peak memory of a realization %s MB\n' "$memory"
done
