#!/usr/bin/env bash
# A tiny sweep on a real one-node Slurm cluster (scripts/slurm_local.sh) against the same sweep
# run here with `sweep run -j 2`: sweep.csv must be byte-identical once the wall-clock columns
# (wall_time_s, real_time_factor, *_ms, host) are dropped. Every array task must have completed,
# with exit 0 and its own log. Fails, with the daemons' own log lines, when they cannot start.
# Usage: test_slurm_sweep.sh SOMASIM PLUGIN_DIR SOURCE_DIR
set -euo pipefail

somasim="$1"
export SOMASIM_PLUGIN_PATH="$2"
src="$3"
sweep_file="$src/tests/slurm/tiny_sweep.yaml"
runs=4                  # 2 offsets x 2 seeds
wait_s="${SLURM_TEST_WAIT_S:-240}" # for the whole array

work="$(mktemp -d "${TMPDIR:-/tmp}/somasim-slurm-XXXXXX")"
chmod 0755 "$work" # munged runs as the munge user and must reach its files under it
cluster="$work/cluster"
cleanup() {
  local rc=$?
  "$src/scripts/slurm_local.sh" down "$cluster" || rc=1
  if [ "$rc" -eq 0 ]; then
    rm -rf "$work"
  else
    echo "test_slurm_sweep: FAILED; files kept in $work" >&2
  fi
  exit "$rc"
}
trap cleanup EXIT
trap 'exit 130' INT TERM

fail() {
  echo "test_slurm_sweep: $*" >&2
  exit 1
}

# Prints a CSV file without the columns whose header is a wall-clock one. Fields are split
# outside double quotes only; the kept fields are printed as they were written.
drop_wall_clock() {
  local line rest field keep=() first=1 i out
  local re='^("([^"]|"")*"|[^,"]*)(,|$)'
  while IFS= read -r line || [ -n "$line" ]; do
    local fields=()
    rest="$line"
    while :; do
      [[ "$rest" =~ $re ]] || fail "$1: cannot split CSV line: $line"
      field="${BASH_REMATCH[1]}"
      fields+=("$field")
      rest="${rest:${#BASH_REMATCH[0]}}"
      [ -n "${BASH_REMATCH[3]}" ] || break
    done
    if [ "$first" -eq 1 ]; then
      first=0
      for i in "${!fields[@]}"; do
        case "${fields[i]}" in
          wall_time_s | real_time_factor | host | *_ms) ;;
          *) keep+=("$i") ;;
        esac
      done
    fi
    out=""
    for i in "${keep[@]}"; do out+="${fields[i]-},"; done
    printf '%s\n' "${out%,}"
  done <"$1"
}

# 1. The cluster.
start=$SECONDS
"$src/scripts/slurm_local.sh" up "$cluster" || fail "the one-node Slurm cluster did not start (its daemons' errors above)"
export SLURM_CONF="$cluster/slurm.conf"
echo "cluster up after $((SECONDS - start)) s"

# 2. The sweep as a job array, throttled to 2 tasks at once.
slurm_out="$work/slurm"
submit_log="$work/submit.txt"
"$somasim" sweep slurm "$sweep_file" --out "$slurm_out" --submit --array-throttle 2 \
  >"$submit_log" || {
  cat "$submit_log"
  fail "sweep slurm --submit failed"
}
cat "$submit_log"
[ "$(sed -n 1p "$submit_log")" = "$slurm_out/sweep.sbatch" ] ||
  fail "sweep slurm did not print the script's path first"
job="$(sed -n 2p "$submit_log")"
[[ "$job" =~ ^[0-9]+$ ]] || fail "sweep slurm --submit printed no job id (line 2: '$job')"
grep -qx "#SBATCH --array=0-$((runs - 1))%2" "$slurm_out/sweep.sbatch" ||
  fail "sweep.sbatch has no '#SBATCH --array=0-$((runs - 1))%2' line"

deadline=$((SECONDS + wait_s))
while [ -n "$(squeue -h -j "$job" 2>/dev/null)" ]; do
  [ "$SECONDS" -lt "$deadline" ] || {
    squeue -j "$job" >&2 || true
    fail "job array $job still queued or running after $wait_s s"
  }
  sleep 0.5
done
echo "array $job done after $((SECONDS - start)) s"

# Every task completed with exit code 0 under the requested throttle, and wrote its log.
info="$(scontrol -o show job "$job")"
for ((i = 0; i < runs; i++)); do
  task="$(grep -E "ArrayJobId=$job ArrayTaskId=$i " <<<"$info")" ||
    fail "scontrol knows no task $i of job $job: $info"
  [[ "$task" == *" JobState=COMPLETED "* && "$task" == *" ExitCode=0:0 "* ]] ||
    fail "task $i of job $job did not complete with exit 0: $task"
  [[ "$task" == *" ArrayTaskThrottle=2 "* ]] || fail "task $i of job $job is not throttled to 2: $task"
  [ -f "$slurm_out/logs/${job}_$i.out" ] || fail "no log $slurm_out/logs/${job}_$i.out"
  [ -f "$slurm_out/logs/${job}_$i.err" ] || fail "no log $slurm_out/logs/${job}_$i.err"
done
n_logs="$(find "$slurm_out/logs" -name "${job}_*.out" | wc -l)"
[ "$n_logs" -eq "$runs" ] || fail "$n_logs task logs in $slurm_out/logs, expected $runs"
"$somasim" sweep collect "$slurm_out"

# 3. The same sweep here, two at a time.
local_out="$work/local"
"$somasim" sweep run "$sweep_file" -j 2 --out "$local_out"
"$somasim" sweep collect "$local_out"

# 4. Same table, whichever engine ran it.
for d in "$slurm_out" "$local_out"; do
  lines="$(wc -l <"$d/sweep.csv")"
  [ "$lines" -eq $((runs + 1)) ] || fail "$d/sweep.csv has $lines lines, expected $((runs + 1))"
  [ "$(grep -c ',completed,' "$d/sweep.csv")" -eq "$runs" ] ||
    fail "$d/sweep.csv: not every run completed"
  drop_wall_clock "$d/sweep.csv" >"$d/sweep.compared.csv"
done
head -n 1 "$slurm_out/sweep.csv" | grep -q ',wall_time_s' || fail "sweep.csv has no wall_time_s column"
if head -n 1 "$slurm_out/sweep.compared.csv" | grep -qE '(^|,)(wall_time_s|real_time_factor|host)(,|$)'; then
  fail "wall-clock columns were not dropped"
fi
cmp "$slurm_out/sweep.compared.csv" "$local_out/sweep.compared.csv" || {
  diff "$slurm_out/sweep.compared.csv" "$local_out/sweep.compared.csv" >&2 || true
  fail "sweep.csv differs between Slurm and 'sweep run -j 2' (wall-clock columns dropped)"
}
echo "sweep.csv identical (Slurm vs local -j 2, wall-clock columns dropped); $((SECONDS - start)) s"
