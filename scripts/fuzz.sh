#!/usr/bin/env bash
# Builds the libFuzzer targets of the input readers (fuzz/: scene and FAB files) with clang,
# AddressSanitizer and UndefinedBehaviorSanitizer, and runs each for SECONDS (default 60)
# from the seed corpus in fuzz/corpus. A crash, a sanitizer report, a hang (one input over 10
# s), an allocation over 512 MB or 2 GB in all, or any exception other than io::InputError
# (exit 2 for users)
# fails the script; the input that did it is left in build-fuzz/artifacts/.
#   bash scripts/fuzz.sh            # 60 s per target (CI)
#   bash scripts/fuzz.sh 3600       # an hour per target
#   build-fuzz/fuzz_scene build-fuzz/artifacts/crash-...   # replay one input
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
cmake -S fuzz -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_COMPILER=clang++-14 > /dev/null
cmake --build build-fuzz -j"$(nproc)"
mkdir -p build-fuzz/artifacts
for target in scene fab; do
  # New inputs go to a scratch corpus; fuzz/corpus/<target> is read only.
  scratch="build-fuzz/corpus-$target"
  mkdir -p "$scratch"
  echo "fuzz: $target for $seconds s"
  log="build-fuzz/fuzz_$target.log"
  # Leak checking is off: at exit LeakSanitizer scans the whole heap, which took minutes after
  # an input that had grown it to the memory limit (the readers keep nothing between inputs).
  # A smaller quarantine keeps AddressSanitizer's resident memory near 200 MB; one allocation
  # over 512 MB is reported at once with its stack (an RSS overflow makes libFuzzer print a heap
  # profile first, which can take minutes: the outer timeout bounds it).
  status=0
  ASAN_OPTIONS=quarantine_size_mb=64 timeout $((seconds + 300)) \
    "build-fuzz/fuzz_$target" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -malloc_limit_mb=512 -detect_leaks=0 -print_final_stats=1 \
    -artifact_prefix=build-fuzz/artifacts/ -dict="fuzz/$target.dict" \
    "$scratch" "fuzz/corpus/$target" > "$log" 2>&1 || status=$?
  grep -E "^(#[0-9]+ +DONE|stat::number_of_executed_units|stat::peak_rss_mb)" "$log" || true
  if [ "$status" -ne 0 ]; then
    grep -v -E "^(#[0-9]+|INFO:)" "$log" | head -60 >&2
    echo "fuzz: $target failed (exit $status); the input is in build-fuzz/artifacts/," \
      "the log in $log" >&2
    exit 1
  fi
done
echo "fuzz: no crash, hang or unexpected error"
