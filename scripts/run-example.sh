#!/usr/bin/env bash
# Builds rockmass and runs the Xiangjiaba example end to end with one command, `rockmass
# run`: the discrete fracture network, the blocks, rock quality (RQD balls, virtual
# boreholes, the RQD/P32 grid), the 3D DDA of the dam's foundation under self-weight and
# water, the overload method and the strength reduction, and the figures. About 3-4 minutes of run on
# 2 free cores (docs/xiangjiaba.md). Outputs go to out/xiangjiaba/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup-debian.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)" --target rockmass
build/app/rockmass run examples/xiangjiaba/scene.yaml -o out/xiangjiaba
