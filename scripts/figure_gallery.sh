#!/usr/bin/env bash
# One figure of every kind somasim draws, from short runs: the PPS landscape, the cameras'
# contact sheet, the skin layout, a
# presentation trace, the body-schema estimation/reaching/closed-loop and particle figures, and a
# sweep summary. Copies each figure (PNG, and its SVG where the build writes one) to OUT as
# KIND.png / KIND.svg. Used to compare figures across builds (e.g. before and after a change).
# Usage: [SOMASIM=path/to/somasim] scripts/figure_gallery.sh OUT
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:?usage: scripts/figure_gallery.sh OUT}
somasim=$(realpath "${SOMASIM:-build/bin/somasim}")
mkdir -p "$out"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# run NAME CONFIG [--set ...]: runs CONFIG into $work/NAME.
run() {
  local name=$1 config=$2
  shift 2
  "$somasim" run "configs/$config" --out "$work/$name" "$@" >"$work/$name.log" 2>&1 || {
    echo "figure_gallery: $config failed; see its log:" >&2
    tail -5 "$work/$name.log" >&2
    exit 1
  }
}
# keep KIND FILE: copies FILE (a PNG) and its SVG, if any, to OUT/KIND.{png,svg}.
keep() {
  local kind=$1 png=$2
  cp "$png" "$out/$kind.png"
  if [ -f "${png%.png}.svg" ]; then cp "${png%.png}.svg" "$out/$kind.svg"; fi
}

run landscape pps_single_taxel_offset.yaml
keep landscape "$(ls "$work"/landscape/figures/landscape_*.png | head -1)"
run cameras camera_demo.yaml
keep stereo_frames "$work/cameras/figures/stereo_frames.png"
run skin ball_on_forearm.yaml
keep skin_layout "$work/skin/figures/skin_layout.png"
run avoidance pps_avoidance.yaml --set nodes.thrower.params.approaches=4
keep presentation_trace "$(ls "$work"/avoidance/figures/presentation_*.png | head -1)"
run reaching body_schema_reaching.yaml --set nodes.reach.params.starts_per_target=1 \
  --set nodes.reach.params.repetitions=1
for kind in estimation reaching closed_loop; do
  keep "body_schema_$kind" "$work/reaching/figures/body_schema_$kind.png"
done
run particles body_schema_particles.yaml --set nodes.reach.params.starts_per_target=1 \
  --set 'nodes.filter.params.compare_particles=[50, 100]'
keep body_schema_particles "$work/particles/figures/body_schema_particles.png"
"$somasim" sweep run -j "$(nproc)" --out "$work/sweep" configs/sweeps/pps_learn_offsets.yaml \
  >"$work/sweep.log" 2>&1
"$somasim" sweep collect "$work/sweep" >>"$work/sweep.log" 2>&1
keep sweep_summary "$(ls "$work"/sweep/*.png | head -1)"
echo "figures in $out:"
ls "$out"
