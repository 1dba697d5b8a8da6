#!/usr/bin/env bash
# The long run of the schema-driven parameter fuzzer (tests/robust/param_fuzz.cpp): every plugin
# alone in the test harness for ALONE seconds, then every plugin inside the smallest shipped
# experiment that uses it for CONFIG seconds. Writes param-fuzz-report.txt (cases per plugin and
# outcome, every violation with its case) and exits 1 if an invariant was violated.
# Usage: scripts/param_fuzz.sh [ALONE_SECONDS [CONFIG_SECONDS [SEED]]]   (after scripts/setup.sh)
set -euo pipefail
cd "$(dirname "$0")/.."
alone="${1:-900}"
config="${2:-1260}"
seed="${3:-11}"
report=param-fuzz-report.txt
status=0
: >"$report"
echo "== alone in the harness, ${alone} s, seed ${seed}" | tee -a "$report"
build/bin/somasim_param_fuzz --seconds "$alone" --seed "$seed" --case-seconds 60 2>&1 |
  tee -a "$report" || status=1
echo "== in the shipped experiments (configs/), ${config} s, seed $((seed + 1))" | tee -a "$report"
build/bin/somasim_param_fuzz --seconds "$config" --seed "$((seed + 1))" --configs configs \
  --case-seconds 120 2>&1 | tee -a "$report" || status=1
exit $status
