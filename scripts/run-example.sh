#!/usr/bin/env bash
# Builds rockmass and runs the Xiangjiaba example as far as the project goes today: the
# discrete fracture network, then rock quality (RQD balls, virtual boreholes), and the
# stereonet figure. Outputs go to out/xiangjiaba/ (RQD in out/xiangjiaba/rqd/: every
# command writes its own summary.json).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup-debian.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)" --target rockmass
build/app/rockmass dfn examples/xiangjiaba/scene.yaml -o out/xiangjiaba
build/app/rockmass rqd examples/xiangjiaba/scene.yaml -o out/xiangjiaba/rqd
/usr/bin/python3 scripts/figures/stereonet.py out/xiangjiaba/fractures.csv \
  -o out/xiangjiaba/stereonet.png --sets J1,J2,J3,J4,J5
