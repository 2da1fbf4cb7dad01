#!/usr/bin/env bash
# Test helper launched by the node rostests: generates a bag with make_synthetic_bag into a fresh
# WORK_DIR (synthetic.bag + truth.yaml), then plays it with rosbag play --clock.
# Usage: play_synthetic_bag.sh WORK_DIR RATE [generator options...]
# (roslaunch's own __name:=/__log:= arguments are ignored.)
set -euo pipefail
export PATH=/usr/bin:/bin:$PATH
work_dir="$1"; rate="$2"; shift 2
gen_args=()
for a in "$@"; do
  case "$a" in __*) ;; *) gen_args+=("$a") ;; esac
done
rm -rf "$work_dir"
mkdir -p "$work_dir"
rosrun thermal_lidar_calibration make_synthetic_bag --output "$work_dir/synthetic.bag" --truth "$work_dir/truth.yaml" "${gen_args[@]}" \
  > "$work_dir/generator.log" 2>&1 || { cat "$work_dir/generator.log" >&2; exit 1; }
# --delay: wait after advertising each topic so that the node's subscribers are connected before
# the first frames go out. Without it a loaded machine lost the first ~2 s of the drive (the node
# kept its first pair at 1.8 s, calibrate_bag at 0.0 s) and node_bag stopped at 28 of 30 pairs.
exec rosbag play --clock -q --delay 2 -r "$rate" "$work_dir/synthetic.bag"
