#!/usr/bin/env bash
# Memory and undefined-behaviour checks, and fuzzing (clang):
#  1. build-san/ (AddressSanitizer + UndefinedBehaviorSanitizer; any finding fails its test):
#     the tests labelled 'core' — every library's tests and the CLI's bad-input catalogue —
#     or, with --all, the whole suite (slow: Bullet and whole experiments under ASan);
#  2. build-fuzz/ (the same sanitizers plus libFuzzer coverage): every fuzz target for
#     SOMASIM_FUZZ_SECONDS (default 20) seconds from its seed corpus.
# The builds are apart so that the suite runs without libFuzzer's coverage instrumentation
# (slower, and one loader test once failed only in the combined build; it passes under
# ASan+UBSan alone, at -O0 and under valgrind).
# Usage: scripts/sanitize.sh [--all | --fuzz-only]   (after scripts/setup.sh)
#   --fuzz-only: stage 2 only (what scripts/test.sh runs in CI; scripts/test.sh --full runs both).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${SOMASIM_FUZZ_SECONDS:-20}"
san="${SOMASIM_SAN_BUILD_DIR:-build-san}"
fuzz="${SOMASIM_FUZZ_BUILD_DIR:-build-fuzz}"
label=(-L core)
target=(--target somasim_core_tests)
suite=1
case "${1:-}" in
  "") ;;
  --all) label=() target=() ;;
  --fuzz-only) suite=0 ;;
  *) echo "usage: scripts/sanitize.sh [--all | --fuzz-only]" >&2; exit 2 ;;
esac
# System libraries' own never-freed caches (fonts, Mesa) are not ours to report; tests that set
# LSAN_OPTIONS themselves name the same file.
export LSAN_OPTIONS="suppressions=$PWD/tests/lsan_suppressions.txt"

if [ "$suite" = 1 ]; then
  echo "== ASan+UBSan build ($san/)"
  CC=clang CXX=clang++ cmake -S . -B "$san" -G Ninja -DCMAKE_BUILD_TYPE=Sanitize \
    -DSOMASIM_SANITIZE=ON -DSOMASIM_BUILD_BENCHMARKS=OFF >/dev/null
  cmake --build "$san" --parallel "$(nproc)" "${target[@]}"
  echo "== tests under ASan+UBSan (${label[*]:-all})"
  # Style checks are the same in every build: they run once, in build/.
  ctest --test-dir "$san" --output-on-failure --parallel "$(nproc)" --timeout 1800 \
    -E '^(tidy_check|format_check)$' "${label[@]}"
fi

echo "== fuzz targets ($fuzz/), ${seconds} s each"
CC=clang CXX=clang++ cmake -S . -B "$fuzz" -G Ninja -DCMAKE_BUILD_TYPE=Sanitize \
  -DSOMASIM_FUZZ=ON -DSOMASIM_BUILD_BENCHMARKS=OFF -DSOMASIM_FUZZ_SECONDS="$seconds" >/dev/null
cmake --build "$fuzz" --parallel "$(nproc)" --target somasim_fuzz_targets
ctest --test-dir "$fuzz" --output-on-failure --timeout $((seconds * 10)) -L fuzz
