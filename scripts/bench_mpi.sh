#!/usr/bin/env bash
# The body-schema filter step for M particles spread over 1 and 2 MPI ranks, in one session
# (tests/bench/bench_body_schema_mpi.cpp; README "MPI"). Usage: scripts/bench_mpi.sh [BUILD_DIR] [M] [STEPS]
set -euo pipefail
build=${1:-build}
m=${2:-2000}
steps=${3:-10}
bench="$build/bin/bench_body_schema_mpi"
[[ -x $bench ]] || { echo "error: $bench not built (cmake --build $build --target bench_body_schema_mpi)" >&2; exit 2; }
mpirun=(mpirun --allow-run-as-root --oversubscribe --bind-to none)
echo "== $(nproc) cores; load: $(uptime)"
echo "== 1 rank, 2 render threads (the whole node)"
"${mpirun[@]}" -n 1 "$bench" "$m" 2 "$steps"
echo "== 1 rank, 1 render thread"
"${mpirun[@]}" -n 1 "$bench" "$m" 1 "$steps"
echo "== 2 ranks, 1 render thread each"
"${mpirun[@]}" -n 2 "$bench" "$m" 1 "$steps"
echo "== load after: $(uptime)"
