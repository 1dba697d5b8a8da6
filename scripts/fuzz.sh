#!/usr/bin/env bash
# Runs every libFuzzer target for SECONDS each (default 600) and writes a report
# (fuzz-report.txt: executions, coverage, corpus size, crashes). Findings (crash-*, leak-*,
# timeout-*, oom-* files) are kept in build-fuzz/fuzz-findings/ ($SOMASIM_FUZZ_BUILD_DIR).
# Usage: scripts/fuzz.sh [SECONDS]   (builds build-fuzz/ first, as scripts/sanitize.sh does)
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-600}"
dir="${SOMASIM_FUZZ_BUILD_DIR:-build-fuzz}"
CC=clang CXX=clang++ cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Sanitize \
  -DSOMASIM_FUZZ=ON -DSOMASIM_BUILD_BENCHMARKS=OFF >/dev/null
targets=(fuzz_experiment_loader fuzz_robot_loader fuzz_learned_map fuzz_ini_import fuzz_sweep_file
  fuzz_set_values)
cmake --build "$dir" --parallel "$(nproc)" --target somasim_fuzz_targets
findings="$dir/fuzz-findings"
mkdir -p "$findings"
report=fuzz-report.txt
: >"$report"
status=0
for t in "${targets[@]}"; do
  corpus="$dir/tests/fuzz/corpus/$t"
  mkdir -p "$corpus"
  seeds=$(ctest --test-dir "$dir" -R "^$t\$" --show-only=json-v1 |
    python3 -c 'import json,sys; c=json.load(sys.stdin)["tests"][0]["command"]; i=c.index("-print_final_stats=1"); print(" ".join(c[i+2:]))')
  echo "== $t: $seconds s"
  set +e
  # shellcheck disable=SC2086
  ASAN_OPTIONS=hard_rss_limit_mb=2560 timeout -s KILL $((seconds + 120)) \
    "$dir/bin/$t" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 -max_len=131072 \
    -print_final_stats=1 -artifact_prefix="$findings/$t-" "$corpus" $seeds >"$findings/$t.log" 2>&1
  rc=$?
  set -e
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$findings/$t.log" | grep -o '[0-9]*$' || echo 0)
  cov=$(grep -o 'cov: [0-9]*' "$findings/$t.log" | tail -1 || true)
  printf '%-24s exit %-3s %s s  %s executions  %s  corpus %s files\n' "$t" "$rc" "$seconds" \
    "$runs" "$cov" "$(ls "$corpus" | wc -l)" | tee -a "$report"
  [ "$rc" -eq 0 ] || status=1
done
ls "$findings" | grep -E '^fuzz_.*-(crash|leak|timeout|oom|slow-unit)-' | sed 's/^/finding: /' | tee -a "$report" || true
exit $status
