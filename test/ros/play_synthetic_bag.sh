#!/usr/bin/env bash
# Test helper launched by the node rostests: generates a bag with make_synthetic_bag into a fresh
# WORK_DIR (synthetic.bag + truth.yaml), then plays it with paced_bag_player --clock: as fast as
# calibration_node takes it and never faster, so the node sees every frame whatever the machine
# (paced_bag_player.cpp says why and lists its options).
# Usage: play_synthetic_bag.sh WORK_DIR [PLAYER_OPTIONS...] -- [GENERATOR_OPTIONS...]
# (roslaunch's own __name:=/__log:= arguments are passed to the player.)
set -euo pipefail
export PATH=/usr/bin:/bin:$PATH
work_dir="$1"; shift
player_args=()
gen_args=()
ros_args=()
seen_separator=""
for a in "$@"; do
  case "$a" in
    __*) ros_args+=("$a") ;;
    --) seen_separator=1 ;;
    *) if [ -n "$seen_separator" ]; then gen_args+=("$a"); else player_args+=("$a"); fi ;;
  esac
done
if [ -z "$seen_separator" ]; then
  echo "play_synthetic_bag.sh: no '--' between the player's and the generator's options" >&2
  exit 2
fi
rm -rf "$work_dir"
mkdir -p "$work_dir"
rosrun thermal_lidar_calibration make_synthetic_bag --output "$work_dir/synthetic.bag" --truth "$work_dir/truth.yaml" "${gen_args[@]}" \
  > "$work_dir/generator.log" 2>&1 || { cat "$work_dir/generator.log" >&2; exit 1; }
exec rosrun thermal_lidar_calibration paced_bag_player "$work_dir/synthetic.bag" --clock "${player_args[@]}" "${ros_args[@]}"
