#!/usr/bin/env bash
# The speed/accuracy trade of docs/TRADE.md: for the default scene, the A-line skirt and GarmentCode's shirt on
# mean_all, the drape's, the preview's and the pipeline's settings against one reference drape per scene (kept in
# build/trade/, reused by a rerun), then the Pareto plot and the GUI's slider levels from the committed reports.
#   bash bench/trade.sh [SCENE...]     (SCENE: default aline_skirt shirt; default: all three)
# Writes docs/trade/<scene>_<stage>.json, docs/trade/levels/<scene>.json, docs/trade_<stage>.png and assets/trade/speed_accuracy_levels.json.
set -euo pipefail
cd "$(dirname "$0")/.."
drape=build/app/drape
rounds="--rounds 2"  # every run twice, interleaved; the faster round counts
mkdir -p build/trade docs/trade
shared=../shared/data/garmentcode

scene_args() {
  case "$1" in
    default) echo "assets/scenes/default.json" ;;
    aline_skirt) echo "assets/scenes/aline_skirt.json" ;;
    shirt) echo "$shared/shirt_mean_specification.json --avatar $shared/mean_all.obj --avatar-units m \
--fabric cotton_shirting --set mesh.target_edge_length=0.02" ;;
  esac
}

# The library garments also measure the slider's level candidates, whose finest mesh (1 cm) the reference then
# resolves; the preview and pipeline reports take a 1 cm run too, so that all three share that reference.
library_mesh() { [ "$1" = shirt ] && echo "" || echo "--sweep mesh.target_edge_length=0.01"; }

drape_sweeps="--sweep solver.newton.tolerance=1e-4,1e-2,1e-1 --sweep solver.cg.tolerance=1e-3,1e-1,0.5
  --sweep solver.newton.h_max=5e-4,2e-3,4e-3,8e-3 --sweep mesh.target_edge_length=0.03,0.04
  --sweep contact.avatar_features=false --sweep contact.self_collision=true --sweep solver.damping.air=0
  --sweep solver.damping.bend=0 --sweep fabric.damping=0"
preview_sweeps="--sweep solver.preview.iterations=2,8,16 --sweep solver.preview.domains=1,4
  --sweep solver.preview.time_step=0.004166666666666667,0.016666666666666666"
full_sweeps="--sweep solver.preview.iterations=8 --sweep solver.preview.max_time=0.25,1 --sweep solver.newton.h_max=4e-3"

scenes=("$@")
[ ${#scenes[@]} -eq 0 ] && scenes=(default aline_skirt shirt)
for s in "${scenes[@]}"; do
  args=$(scene_args "$s")
  mesh=$(library_mesh "$s")
  # shellcheck disable=SC2086
  $drape --bench $args --solver drape $drape_sweeps $mesh $rounds --reference "build/trade/$s.ref.json" \
    -o "docs/trade/${s}_drape.json"
  # shellcheck disable=SC2086
  $drape --bench $args --solver preview $preview_sweeps $mesh $rounds --reference "build/trade/$s.ref.json" \
    -o "docs/trade/${s}_preview.json"
  # shellcheck disable=SC2086
  $drape --bench $args --solver full $full_sweeps $mesh $rounds --reference "build/trade/$s.ref.json" \
    -o "docs/trade/${s}_full.json"
  # The slider's level candidates (assets/trade/level_candidates.json), on the library garments only.
  if [ "$s" != shirt ]; then
    mkdir -p docs/trade/levels
    # shellcheck disable=SC2086
    $drape --bench $args --solver drape --levels $rounds --reference "build/trade/$s.ref.json" -o "docs/trade/levels/$s.json"
  fi
done
for stage in drape preview full; do
  $drape --trade-plot docs/trade/*_$stage.json -o "docs/trade_$stage.png"
done
$drape --trade-levels docs/trade/levels/*.json -o assets/trade/speed_accuracy_levels.json
