#!/usr/bin/env bash
# Raw sensors against ideal detections, drive by drive (issue #7): for each drive seed, a raw
# synthetic bag (make_synthetic_bag --raw: full-density /lidar/points, radiometric mono16 image,
# sun-heated posts; it also carries the ideal mask and cluster topics of the same drive) is
# calibrated twice with default settings:
#   detect  calibrate_bag --detect (the built-in detectors on the raw image and points)
#   ideal   calibrate_bag on the ideal mask/cluster topics of the same frames
# and the rotation / translation errors against the truth are printed side by side.
# Each bag is ~400 KB per frame; it is deleted after use.
# Usage: scripts/raw_accuracy.sh [--noise clean|realistic] [--frames N] [SEEDS...]  (default 1 2 3 4 5)
set -euo pipefail
# shellcheck source=scripts/workspace.sh
source "$(dirname "${BASH_SOURCE[0]}")/workspace.sh"
prepare_workspace
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
out="${TLC_ACCURACY_OUT:-$repo/out/raw_accuracy}"
mkdir -p "$out"

field() {  # yaml key path -> value (python3 from Debian, as the ROS tools)
  /usr/bin/python3 -c "import sys, yaml; y = yaml.safe_load(open(sys.argv[1])); print(y$2)" "$1"
}
printf "%-5s %-9s %6s %6s %10s %9s\n" seed mode kept used rot_deg trans_cm
for seed in "${seeds[@]}"; do
  bag="$out/raw.seed$seed.bag"
  "$bin/make_synthetic_bag" --raw --noise "$noise" --frames "$frames" --seed "$seed" \
    --output "$bag" --truth "$out/truth.seed$seed.yaml" > "$out/gen.seed$seed.log" 2>&1
  for mode in detect ideal; do
    result="$out/$mode.$noise.seed$seed.yaml"
    args=()
    [ "$mode" = detect ] && args=(--detect)
    if "$bin/calibrate_bag" --bag "$bag" --output "$result" --truth "$out/truth.seed$seed.yaml" \
        --quiet "${args[@]}" > "$out/$mode.$noise.seed$seed.log" 2>&1; then
      printf "%-5s %-9s %6s %6s %10.4f %9.2f\n" "$seed" "$mode" \
        "$(field "$result" "['pairs_collected']")" "$(field "$result" "['pairs_used']")" \
        "$(field "$result" "['truth']['rotation_error_deg']")" \
        "$(field "$result" "['truth']['translation_error_m'] * 100")"
    else
      printf "%-5s %-9s failed: %s\n" "$seed" "$mode" "$(tail -n 1 "$out/$mode.$noise.seed$seed.log")"
    fi
  done
  rm -f "$bag"
done
