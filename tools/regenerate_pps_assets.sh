#!/usr/bin/env bash
# Regenerates the learned PPS maps in assets/pps/ that the evaluation configs
# (configs/pps_avoidance.yaml, configs/pps_reaching.yaml) load: configs/pps_learn_objects.yaml,
# seed 1, on the paper's 8 D bins, once with the (D, TTC) model and once distance-only.
# Usage: tools/regenerate_pps_assets.sh [path/to/somasim]   (default: build/bin/somasim)
set -euo pipefail
cd "$(dirname "$0")/.."
somasim="${1:-build/bin/somasim}"
out="$(mktemp -d)"
for model in d_ttc distance_only; do
  "$somasim" run configs/pps_learn_objects.yaml --out "$out/$model" \
    --set nodes.pps.params.d_bins=8 --set nodes.pps.params.model="$model" > /dev/null 2>&1
done
# The visual variants' map (configs/pps_*_visual.yaml): objects seen by the eyes, 200 objects.
"$somasim" run configs/pps_learn_visual_objects.yaml --out "$out/visual" \
  --set nodes.thrower.params.approaches=200 --set nodes.pps.params.d_bins=8 \
  --set 'nodes.pps.params.snapshot_events=[]' > /dev/null 2>&1
cp "$out/d_ttc/pps_objects.json" assets/pps/pps_objects.json
cp "$out/distance_only/pps_objects.json" assets/pps/pps_objects_distance_only.json
cp "$out/visual/pps_visual_objects.json" assets/pps/pps_visual_objects.json
echo "assets/pps/pps_objects.json, pps_objects_distance_only.json, pps_visual_objects.json updated (runs in $out)"
