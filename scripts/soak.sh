#!/usr/bin/env bash
# The seed soak: every configs/sweeps/soak_*.yaml (or the names given) run with `somasim sweep
# run -j JOBS` into runs/soak/NAME and collected; prints one table row per sweep (runs,
# completed, failed with seed and error, wall time of the slowest run).
# Usage: [SOMASIM=path/to/somasim] scripts/soak.sh [-j JOBS] [NAME...]
#        (NAME: pps_avoidance for soak_pps_avoidance.yaml)
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc)
if [ "${1:-}" = -j ]; then
  jobs=$2
  shift 2
fi
names=("$@")
if ((${#names[@]} == 0)); then
  for f in configs/sweeps/soak_*.yaml; do
    n=$(basename "$f" .yaml)
    names+=("${n#soak_}")
  done
fi
somasim=${SOMASIM:-build/bin/somasim}  # SOMASIM: another build's binary
status=0
echo "| config | runs | completed | slowest run [s] | failures |"
echo "|---|---|---|---|---|"
for name in "${names[@]}"; do
  out=runs/soak/$name
  "$somasim" sweep run -j "$jobs" --out "$out" "configs/sweeps/soak_$name.yaml" >"$out.log" 2>&1 ||
    status=1
  "$somasim" sweep collect "$out" >/dev/null 2>&1 || status=1
  runs=0 completed=0 slowest=0 failures=""
  for m in "$out"/runs/*/metrics.json; do
    [ -f "$m" ] || continue
    runs=$((runs + 1))
    wall=$(grep -m1 '"wall_time_s"' "$m" | sed 's/.*: *\([0-9.e+-]*\).*/\1/')
    slowest=$(awk -v a="$slowest" -v b="$wall" 'BEGIN { print (b > a) ? b : a }')
    if grep -m1 -q '"status": "completed"' "$m"; then
      completed=$((completed + 1))
    else
      seed=$(grep -m1 '"seed"' "$m" | sed 's/.*: *\([0-9]*\).*/\1/')
      error=$(grep -m1 '"error"' "$m" | sed 's/^ *"error": *//; s/,$//')
      failures+="seed $seed: $error; "
      status=1
    fi
  done
  printf '| %s | %d | %d | %.0f | %s |\n' "$name" "$runs" "$completed" "$slowest" "${failures:-none}"
done
exit $status
