#!/usr/bin/env bash
# Builds everything (library, program, tests, benchmarks), runs all tests with CTest, and
# checks the verification manual: the tests record every comparison with a hand value into
# build/verification (tests/support/verification.h), and docs/verification.md must be what
# scripts/verification.py writes from those records (the script fails with a diff otherwise;
# regenerate it with `python3 scripts/verification.py` and commit it), then fuzzes the scene
# and FAB readers for 60 s each (scripts/fuzz.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup-debian.sh
# Formatting first (seconds): every tracked C++ source as clang-format writes it (.clang-format).
if [ -d .git ]; then
  git ls-files -z '*.cpp' '*.h' | xargs -0 clang-format-14 --dry-run -Werror
else
  find app bench blocks dda3d fuzz geometry io rqd scenarios scene_model tests \( -name '*.cpp' -o -name '*.h' \) -print0 |
    xargs -0 clang-format-14 --dry-run -Werror
fi
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)"
# Absolute: CTest runs each test in its own working directory.
export ROCKMASS_VERIFICATION_DIR="$PWD/build/verification"
rm -rf "$ROCKMASS_VERIFICATION_DIR"
mkdir -p "$ROCKMASS_VERIFICATION_DIR"
ctest --test-dir build --output-on-failure -j"$(nproc)"
/usr/bin/python3 scripts/verification.py --records "$ROCKMASS_VERIFICATION_DIR" --check
# The readers' fuzz targets, 60 s each (fuzz/; bash scripts/fuzz.sh 3600 to run longer).
bash scripts/fuzz.sh 60
