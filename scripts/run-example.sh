#!/usr/bin/env bash
# Builds rockmass and runs the Xiangjiaba example as far as the project goes today (the
# discrete fracture network). Outputs go to out/xiangjiaba/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup-debian.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)" --target rockmass
build/app/rockmass dfn examples/xiangjiaba/scene.yaml -o out/xiangjiaba
