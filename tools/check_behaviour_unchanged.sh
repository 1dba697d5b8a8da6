#!/usr/bin/env bash
# check_behaviour_unchanged.sh — run the shipped experiments with two builds and compare outputs.
#
# Purpose: a change that must not alter behaviour (the restructuring of the source tree into
# core/framework, core/<domain> libraries, ...) has to leave every output of every shipped
# config unchanged: the same CSVs, learned files (JSON maps), figures and metrics.json
# (wall-clock fields aside) — text identical, numbers bit for bit. Only where a shared helper
# was knowingly reordered may numbers differ, within a stated relative tolerance (--rel-tol).
#
# Usage:
#   tools/check_behaviour_unchanged.sh [options] OLD_SOMASIM NEW_SOMASIM [CONFIG...]
#
#   OLD_SOMASIM, NEW_SOMASIM  the `somasim` executable of each revision, e.g.
#                             ../baseline/build/bin/somasim build/bin/somasim
#   CONFIG...                 config names (pps_reaching), file names (pps_reaching.yaml) or
#                             paths (configs/pps_reaching.yaml; only the file name is used).
#                             Default: every configs/*.yaml of the new tree.
#
#   Each executable runs the config of the same name from the configs/ folder of its own source
#   tree (so each loads its own assets/ through the configs' ../assets paths, and its own
#   plugins: the ones next to the executable, build/lib/somasim/plugins; SOMASIM_PLUGIN_PATH is
#   unset so that both cannot load the same plugins). The folder is $(dirname EXE)/../../configs
#   (EXE = build/bin/somasim), or set it with the environment variables OLD_CONFIGS / NEW_CONFIGS.
#
# Options:
#   --rel-tol X      relative tolerance passed to compare_runs.py (default 0: exact)
#   --abs-tol X      absolute tolerance passed to compare_runs.py (default 0)
#   --work DIR       scratch folder for the runs (default: a new mktemp -d folder; kept, its
#                    path is printed). Runs go to DIR/old/<config> and DIR/new/<config>.
#   --old-runs DIR   reuse existing run folders of the old build, DIR/<config> (made by
#                    `somasim run configs/<config>.yaml --out DIR/<config>`), instead of running
#                    the old executable; OLD_SOMASIM may then be given as "-".
#   --nice N         run somasim under `nice -n N` (default 10)
#   --set PATH=VALUE passed to every run of both executables (repeatable), e.g.
#                    --set duration_s=20 to shorten long experiments alike
#   -h, --help       this text
#
# Each run is `somasim run CONFIG --out DIR --quiet`, one at a time. Then
# tools/compare_runs.py compares each pair (log.txt and experiment.resolved.yaml are ignored;
# metrics.json is compared as JSON without wall_time_s, real_time_factor, versions and keys
# containing "wall"; PNGs byte for byte, differences in metadata only are reported but pass).
#
# Output: compare_runs.py's findings per config, then a table
#   config  old exit/wall  new exit/wall  result (identical / within tol / DIFFERENT)
# Exit status: 0 if every config is identical or within tolerance, 1 if any differs (including
# different exit codes or a missing config), 2 on usage errors.
#
# Example (from the new tree's root):
#   tools/check_behaviour_unchanged.sh ../baseline/build/bin/somasim build/bin/somasim \
#       pps_single_taxel pps_single_taxel_offset
#   OLD_CONFIGS=/path/to/old/configs tools/check_behaviour_unchanged.sh --rel-tol 1e-9 OLD NEW

set -u

usage() { sed -n '2,/^set -u/p' "$0" | sed '$d' | sed 's/^# \{0,1\}//'; }

here=$(cd "$(dirname "$0")" && pwd)
compare="$here/compare_runs.py"
rel_tol=0
abs_tol=0
work=""
old_runs=""
nice_level=10
sets=()
positional=()
while [ $# -gt 0 ]; do
  case "$1" in
    --rel-tol) rel_tol=${2:?--rel-tol needs a value}; shift 2 ;;
    --rel-tol=*) rel_tol=${1#*=}; shift ;;
    --abs-tol) abs_tol=${2:?--abs-tol needs a value}; shift 2 ;;
    --abs-tol=*) abs_tol=${1#*=}; shift ;;
    --work) work=${2:?--work needs a folder}; shift 2 ;;
    --work=*) work=${1#*=}; shift ;;
    --old-runs) old_runs=${2:?--old-runs needs a folder}; shift 2 ;;
    --old-runs=*) old_runs=${1#*=}; shift ;;
    --nice) nice_level=${2:?--nice needs a value}; shift 2 ;;
    --set) sets+=(--set "${2:?--set needs PATH=VALUE}"); shift 2 ;;
    --set=*) sets+=(--set "${1#*=}"); shift ;;
    --nice=*) nice_level=${1#*=}; shift ;;
    -h|--help) usage; exit 0 ;;
    --) shift; positional+=("$@"); break ;;
    -?*) echo "check_behaviour_unchanged: unknown option '$1' (see --help)" >&2; exit 2 ;;
    *) positional+=("$1"); shift ;;
  esac
done
if [ ${#positional[@]} -lt 2 ]; then
  echo "usage: $0 [--rel-tol X] [--abs-tol X] [--work DIR] [--old-runs DIR] [--nice N] OLD_SOMASIM NEW_SOMASIM [CONFIG...]" >&2
  exit 2
fi
old_exe=${positional[0]}
new_exe=${positional[1]}
configs=("${positional[@]:2}")

abspath() { (cd "$(dirname "$1")" && echo "$(pwd)/$(basename "$1")"); }

check_exe() {
  if [ ! -x "$1" ]; then echo "check_behaviour_unchanged: not an executable: $1" >&2; exit 2; fi
}
if [ -n "$old_runs" ]; then
  [ -d "$old_runs" ] || { echo "check_behaviour_unchanged: --old-runs: no folder $old_runs" >&2; exit 2; }
  old_runs=$(cd "$old_runs" && pwd)
  [ "$old_exe" = "-" ] || { check_exe "$old_exe"; old_exe=$(abspath "$old_exe"); }
else
  check_exe "$old_exe"; old_exe=$(abspath "$old_exe")
fi
check_exe "$new_exe"; new_exe=$(abspath "$new_exe")

configs_of() {  # $1 = exe, $2 = override
  if [ -n "$2" ]; then (cd "$2" && pwd); return; fi
  (cd "$(dirname "$1")/../../configs" 2>/dev/null && pwd)
}
new_configs=$(configs_of "$new_exe" "${NEW_CONFIGS:-}") || true
if [ -z "$new_configs" ]; then
  echo "check_behaviour_unchanged: no configs folder for $new_exe (set NEW_CONFIGS)" >&2; exit 2
fi
old_configs=""
if [ "$old_exe" != "-" ] || [ -n "${OLD_CONFIGS:-}" ]; then
  old_configs=$(configs_of "$old_exe" "${OLD_CONFIGS:-}") || true
  if [ -z "$old_configs" ] && [ -z "$old_runs" ]; then
    echo "check_behaviour_unchanged: no configs folder for $old_exe (set OLD_CONFIGS)" >&2; exit 2
  fi
fi

if [ ${#configs[@]} -eq 0 ]; then
  for f in "$new_configs"/*.yaml; do [ -e "$f" ] && configs+=("$(basename "$f" .yaml)"); done
  # a config only the old tree has is a difference too
  if [ -n "$old_configs" ]; then
    for f in "$old_configs"/*.yaml; do
      n=$(basename "$f" .yaml)
      [ -e "$new_configs/$n.yaml" ] || configs+=("$n")
    done
  fi
fi
if [ ${#configs[@]} -eq 0 ]; then
  echo "check_behaviour_unchanged: no configs in $new_configs" >&2; exit 2
fi

if [ -z "$work" ]; then work=$(mktemp -d "${TMPDIR:-/tmp}/somasim-behaviour.XXXXXX"); fi
mkdir -p "$work/old" "$work/new" || exit 2
work=$(cd "$work" && pwd)

# Both builds must load their own plugins only.
unset SOMASIM_PLUGIN_PATH

echo "old: ${old_exe}  configs: ${old_configs:-"(not used)"}${old_runs:+  reusing runs in $old_runs}"
echo "new: ${new_exe}  configs: ${new_configs}"
echo "runs in: $work   tolerance: rel $rel_tol, abs $abs_tol"

# run EXE CONFIG_FILE OUT_DIR -> sets run_rc, run_wall
run() {
  local exe=$1 cfg=$2 out=$3 t0 t1
  rm -rf "$out"
  t0=$(date +%s.%N)
  nice -n "$nice_level" "$exe" run "$cfg" --out "$out" --quiet "${sets[@]}" >"$out.stdout" \
    2>"$out.stderr"
  run_rc=$?
  t1=$(date +%s.%N)
  run_wall=$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.1f", b - a }')
}

declare -a rows
fail=0
for c in "${configs[@]}"; do
  name=$(basename "$c"); name=${name%.yaml}
  echo
  echo "=== $name"
  old_cfg="${old_configs:+$old_configs/$name.yaml}"
  new_cfg="$new_configs/$name.yaml"
  old_dir="$work/old/$name"; new_dir="$work/new/$name"
  old_state=""; new_state=""
  if [ -n "$old_runs" ] && [ -f "$old_runs/$name/metrics.json" ]; then
    old_dir="$old_runs/$name"; old_state="reused"
  elif [ "$old_exe" = "-" ]; then
    old_state="missing"; echo "no run $old_runs/$name and no old executable"
  elif [ ! -f "$old_cfg" ]; then
    old_state="missing"; echo "no config $old_cfg"
  else
    run "$old_exe" "$old_cfg" "$old_dir"; old_state="rc=$run_rc ${run_wall}s"
    [ "$run_rc" -eq 0 ] || { echo "old exited $run_rc:"; tail -3 "$old_dir.stderr"; }
  fi
  if [ ! -f "$new_cfg" ]; then
    new_state="missing"; echo "no config $new_cfg"
  else
    run "$new_exe" "$new_cfg" "$new_dir"; new_state="rc=$run_rc ${run_wall}s"
    [ "$run_rc" -eq 0 ] || { echo "new exited $run_rc:"; tail -3 "$new_dir.stderr"; }
  fi
  result="DIFFERENT"
  if [ "$old_state" != "missing" ] && [ "$new_state" != "missing" ]; then
    old_rc=${old_state#rc=}; old_rc=${old_rc%% *}
    new_rc=${new_state#rc=}; new_rc=${new_rc%% *}
    if [ "$old_state" != "reused" ] && [ "$old_rc" != "$new_rc" ]; then
      echo "exit codes differ: old $old_rc, new $new_rc"
    fi
    summary=$(python3 "$compare" "$old_dir" "$new_dir" --rel-tol "$rel_tol" --abs-tol "$abs_tol")
    cmp_rc=$?
    printf '%s\n' "$summary"
    if [ $cmp_rc -eq 0 ]; then
      if printf '%s\n' "$summary" | tail -1 | grep -q ' 0 within tolerance,'; then
        result="identical"
      else
        result="within tol"
      fi
    fi
    if [ "$old_state" != "reused" ] && [ "$old_rc" != "$new_rc" ]; then result="DIFFERENT"; fi
  fi
  [ "$result" = "DIFFERENT" ] && fail=1
  rows+=("$(printf '%-28s %-16s %-16s %s' "$name" "$old_state" "$new_state" "$result")")
done

echo
printf '%-28s %-16s %-16s %s\n' "config" "old" "new" "result"
printf '%s\n' "${rows[@]}"
if [ $fail -ne 0 ]; then
  echo "behaviour CHANGED (rel-tol $rel_tol); runs kept in $work"
  exit 1
fi
echo "behaviour unchanged (rel-tol $rel_tol); runs in $work"
exit 0
