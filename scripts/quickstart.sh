#!/usr/bin/env bash
# Sets everything up and runs the default experiment: the single-taxel Monte Carlo with noise
# and a -10 cm offset (PPS paper Fig 3). Prints where its results are.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh runtime
build/bin/somasim run configs/pps_single_taxel_offset.yaml --out runs/pps_single_taxel_offset --overwrite
