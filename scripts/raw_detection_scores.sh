#!/usr/bin/env bash
# Detection quality of the two person detectors on raw synthetic drives (issue 7): per modality,
# per-person recall and precision and the share of frames whose people counts agree with the
# truth, for people within 20 m and wholly in view (bench/score_raw_detections.cpp says how each
# is scored). Usage: scripts/raw_detection_scores.sh [--noise clean|realistic] [--frames N] [SEEDS...]
set -euo pipefail
# shellcheck source=scripts/workspace.sh
source "$(dirname "${BASH_SOURCE[0]}")/workspace.sh"
prepare_workspace --bench
noise=clean
frames=1200
seeds=()
while [ $# -gt 0 ]; do
  case "$1" in
    --noise) noise="$2"; shift 2 ;;
    --frames) frames="$2"; shift 2 ;;
    *) seeds+=("$1"); shift ;;
  esac
done
[ ${#seeds[@]} -gt 0 ] || seeds=(1 2 3 4 5)
out="${TLC_ACCURACY_OUT:-$repo/out/raw_detection_scores}"
mkdir -p "$out"
for seed in "${seeds[@]}"; do
  "$bin/make_synthetic_bag" --raw --noise "$noise" --frames "$frames" --seed "$seed" \
    --output "$out/raw$seed.bag" --truth "$out/truth$seed.yaml" > /dev/null 2>&1
  echo "seed $seed ($noise, $frames frames):"
  "$bin/score_raw_detections" "$out/raw$seed.bag" | sed 's/^/  /'
  rm -f "$out/raw$seed.bag"
done
