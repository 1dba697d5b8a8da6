#!/usr/bin/env bash
# `somasim sweep slurm --submit` without sbatch on PATH: exit 2 and a clear message naming what
# to install and where the (still written) script is. No cluster needed.
# Usage: test_sbatch_missing.sh SOMASIM PLUGIN_DIR SOURCE_DIR
set -euo pipefail

somasim="$1"
export SOMASIM_PLUGIN_PATH="$2"
src="$3"
work="$(mktemp -d "${TMPDIR:-/tmp}/somasim-nosbatch-XXXXXX")"
trap 'rm -rf "$work"' EXIT
mkdir "$work/empty_path"
out="$work/sweep"

rc=0
PATH="$work/empty_path" "$somasim" sweep slurm "$src/tests/slurm/tiny_sweep.yaml" --out "$out" \
  --submit >"$work/stdout" 2>"$work/stderr" || rc=$?
expected="error: sbatch not found on PATH: install slurm-client or run on a Slurm login node; the script is at $out/sweep.sbatch"
if [ "$rc" -ne 2 ] || [ "$(cat "$work/stderr")" != "$expected" ]; then
  echo "expected exit 2 and: $expected" >&2
  echo "got exit $rc and: $(cat "$work/stderr")" >&2
  exit 1
fi
[ -x "$out/sweep.sbatch" ] || {
  echo "no executable $out/sweep.sbatch" >&2
  exit 1
}
echo "ok: exit 2, '$expected'"
