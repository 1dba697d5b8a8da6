#!/usr/bin/env bash
# Builds the whole tree with clang, AddressSanitizer + UndefinedBehaviorSanitizer and libFuzzer's
# coverage instrumentation into build-san/ ($SOMASIM_SAN_BUILD_DIR), runs the test suite there (any sanitizer finding fails
# its test) and every fuzz target for a short while (SOMASIM_FUZZ_SECONDS, default 20 s each).
# Usage: scripts/sanitize.sh        (after scripts/setup.sh; scripts/test.sh calls it)
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${SOMASIM_FUZZ_SECONDS:-20}"
dir="${SOMASIM_SAN_BUILD_DIR:-build-san}"

echo "== building with ASan+UBSan and the fuzz targets ($dir/)"
CC=clang CXX=clang++ cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Sanitize \
  -DSOMASIM_FUZZ=ON -DSOMASIM_BUILD_BENCHMARKS=OFF -DSOMASIM_FUZZ_SECONDS="$seconds" >/dev/null
cmake --build "$dir" --parallel "$(nproc)"

echo "== test suite under ASan+UBSan"
# Style checks are the same in every build: run once, in build/.
ctest --test-dir "$dir" --output-on-failure --parallel "$(nproc)" --timeout 1200 \
  -E '^(tidy_check|format_check)$' -LE fuzz

echo "== fuzz targets, ${seconds} s each"
ctest --test-dir "$dir" --output-on-failure --timeout $((seconds * 10)) -L fuzz
