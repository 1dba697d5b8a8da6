#!/usr/bin/env bash
# Sets everything up and runs the test suite.
# Usage: scripts/test.sh [--full]
#   (default: what CI runs) every ctest test, clang-tidy on its CI slice (SOMASIM_TIDY_SCOPE=slice:
#     recently changed sources and a quarter in turn, tests/tidy/tidy_slice.cmake), then every
#     fuzz target for SOMASIM_FUZZ_SECONDS (20) s under ASan+UBSan.
#   --full  clang-tidy over every source, and the 'core' tests rebuilt and run under ASan+UBSan
#     before the fuzzers (scripts/sanitize.sh): about 40 min more on 2 cores.
# SOMASIM_SKIP_SANITIZE=1 skips the sanitizer and fuzz stages.
set -euo pipefail
cd "$(dirname "$0")/.."
full=0
case "${1:-}" in
  "") ;;
  --full) full=1 ;;
  *) echo "usage: scripts/test.sh [--full]" >&2; exit 2 ;;
esac
# Each stage's wall time, printed again at the end (CI keeps only the log's tail).
timings=()
stage() {
  local name=$1 start=$SECONDS
  shift
  "$@"
  timings+=("$name: $((SECONDS - start)) s")
  echo "== $name took $((SECONDS - start)) s"
}
stage "setup and build" scripts/setup.sh full
if [ "$full" = 1 ]; then
  export SOMASIM_TIDY_SCOPE=all
else
  export SOMASIM_TIDY_SCOPE="${SOMASIM_TIDY_SCOPE:-slice}"
fi
stage "test suite" ctest --test-dir build --output-on-failure --parallel "$(nproc)" --timeout 600
if [ "${SOMASIM_SKIP_SANITIZE:-0}" != 1 ]; then
  if [ "$full" = 1 ]; then
    stage "sanitizers and fuzzers" scripts/sanitize.sh
  else
    stage "fuzzers" scripts/sanitize.sh --fuzz-only
  fi
fi
echo "== slowest tests (s):"
sort -k3 -g -r build/Testing/Temporary/CTestCostData.txt 2>/dev/null | awk 'NF == 3' | head -8 || true
printf '== %s\n' "${timings[@]}" "all: ${SECONDS} s"
