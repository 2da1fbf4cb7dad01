#!/usr/bin/env bash
# Test helper launched by the node rostests: puts a bag made by make_synthetic_bag into a fresh
# WORK_DIR (synthetic.bag + truth.yaml), then plays it with paced_bag_player --clock: as fast as
# calibration_node takes it and never faster, so the node sees every frame whatever the machine
# (paced_bag_player.cpp says why and lists its options).
# A drive is generated once per test run: bags are kept in $TLC_TEST_TMP/tlc_bag_cache (a fresh
# directory for each run_tests.sh), one per set of generator options and generator build, and
# linked into WORK_DIR.
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
generator="$(catkin_find --first-only --libexec thermal_lidar_calibration make_synthetic_bag)"
cache_root="${TLC_TEST_TMP:-/tmp}/tlc_bag_cache"
key="$( { stat -c '%s %Y' "$generator"; printf '%s\n' "${gen_args[@]}"; } | md5sum | cut -c1-16)"
cache="$cache_root/$key"
mkdir -p "$cache_root"
(
  flock 9  # one generator per drive, also when tests run side by side
  if [ ! -s "$cache/truth.yaml" ]; then
    rm -rf "$cache.partial"
    mkdir -p "$cache.partial"
    "$generator" --output "$cache.partial/synthetic.bag" --truth "$cache.partial/truth.yaml" "${gen_args[@]}" \
      > "$cache.partial/generator.log" 2>&1 || { cat "$cache.partial/generator.log" >&2; exit 1; }
    mv "$cache.partial" "$cache"
  fi
) 9>"$cache_root/lock"
ln "$cache/synthetic.bag" "$work_dir/synthetic.bag" 2>/dev/null || cp "$cache/synthetic.bag" "$work_dir/synthetic.bag"
cp "$cache/generator.log" "$work_dir/generator.log"
cp "$cache/truth.yaml" "$work_dir/truth.yaml"  # a new file: wait_for_file.sh sees it written now
exec "$(catkin_find --first-only --libexec thermal_lidar_calibration paced_bag_player)" "$work_dir/synthetic.bag" --clock "${player_args[@]}" "${ros_args[@]}"
