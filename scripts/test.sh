#!/usr/bin/env bash
# Sets everything up and runs the whole test suite (what CI runs).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh full
ctest --test-dir build --output-on-failure --parallel "$(nproc)" --timeout 600
# The same suite under ASan+UBSan, and a short run of every fuzz target (scripts/sanitize.sh).
if [ "${SOMASIM_SKIP_SANITIZE:-0}" != 1 ]; then
  scripts/sanitize.sh
fi
