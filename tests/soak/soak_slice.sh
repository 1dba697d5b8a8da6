#!/usr/bin/env bash
# A slice of the seed soak (configs/sweeps/soak_*.yaml) for CI: each named soak sweep at two
# seeds outside the ones the configs were tuned on, run with `somasim sweep run` and collected
# with `sweep collect`; fails unless every run completed.
# Usage: soak_slice.sh SOMASIM SOURCE_DIR OUT_DIR SEEDS NAME...   (SEEDS: a YAML list, "[5, 17]")
set -euo pipefail
somasim=$1 src=$2 out=$3 seeds=$4
shift 4
rm -rf "$out"
mkdir -p "$out"
status=0
for name in "$@"; do
  sweep="$src/configs/sweeps/soak_$name.yaml"
  [ -f "$sweep" ] || { echo "no soak sweep $sweep"; exit 2; }
  dir="$out/$name"
  mkdir -p "$dir"
  # The same sweep with the slice's seeds and the experiment path made absolute.
  sed -e "s|^experiment: \.\./|experiment: $src/configs/|" -e "s|^seeds: .*|seeds: $seeds|" \
    "$sweep" >"$dir/sweep.yaml"
  if ! "$somasim" sweep run -j 2 --out "$dir/runs" "$dir/sweep.yaml"; then
    echo "soak $name: a run failed"
    status=1
  fi
  "$somasim" sweep collect "$dir/runs" >/dev/null
  # Every run's metrics.json must say completed (its first "status" key is the run's own).
  runs=0 completed=0
  for m in "$dir"/runs/runs/*/metrics.json; do
    runs=$((runs + 1))
    if grep -m1 -q '"status": "completed"' "$m"; then
      completed=$((completed + 1))
    else
      echo "  $m: $(grep -m1 '"status"' "$m") $(grep -m1 '"error"' "$m")"
      status=1
    fi
  done
  echo "soak $name: $completed of $runs runs completed"
  [ "$runs" -gt 0 ] || status=1
done
exit $status
