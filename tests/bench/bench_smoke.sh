#!/usr/bin/env bash
# Smoke run of one Google Benchmark executable: every benchmark must produce its figure (a
# result with iterations, no error). No timing is checked. Usage: bench_smoke.sh BENCH [ARGS...]
set -uo pipefail
bench=$1
shift
out=$(mktemp)
trap 'rm -f "$out"' EXIT
"$bench" --benchmark_min_time=0.001 --benchmark_format=json "$@" > "$out"
rc=$?
if [[ $rc -ne 0 ]]; then
  echo "error: $bench exited with $rc" >&2
  exit 1
fi
results=$(grep -c '"run_type"' "$out")
errors=$(grep -c '"error_occurred": true' "$out")
if [[ $results -eq 0 ]]; then
  echo "error: $bench reported no benchmark" >&2
  exit 1
fi
if [[ $errors -ne 0 ]]; then
  echo "error: $bench: $errors of $results benchmarks failed:" >&2
  grep -B3 -A2 '"error_occurred": true' "$out" >&2
  exit 1
fi
echo "$bench: $results benchmarks, each with a figure"
