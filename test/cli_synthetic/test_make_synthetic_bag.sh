#!/usr/bin/env bash
# Smoke test of the make_synthetic_bag CLI (no roscore): exit codes, topics, frame ids, truth keys.
# Usage: test/cli_synthetic/test_make_synthetic_bag.sh [PATH/TO/make_synthetic_bag]
# Registered in test/CMakeLists.txt (through run_as_junit.sh, so catkin counts it).
set -uo pipefail
export PATH=/usr/bin:/bin:$PATH
exe="${1:-make_synthetic_bag}"
dir="$(mktemp -d "${TMPDIR:-/tmp}/tlc_synth_cli.XXXXXX")"
trap 'rm -rf "$dir"' EXIT
failures=0
check() {  # check DESCRIPTION COMMAND...
  local what="$1"; shift
  if "$@" >/dev/null 2>&1; then echo "ok   $what"; else echo "FAIL $what"; failures=$((failures + 1)); fi
}
exit_code() { "$exe" "$@" >/dev/null 2>"$dir/err"; echo $?; }

check "--help exits 0" "$exe" --help
for bad in "" "--output $dir/x.bag --frames 0" "--output $dir/x.bag --rig kitti" \
           "--output $dir/x.bag --no-such-flag" "--output $dir/x.bag --miss-rate 2" "--output $dir/x.bag --seed"; do
  # shellcheck disable=SC2086
  code=$(exit_code $bad)
  check "bad arguments '$bad' exit 2 with one line" test "$code" = 2 -a "$(wc -l < "$dir/err")" = 1
done

check "small fieldsafe bag" "$exe" --output "$dir/a.bag" --frames 40 --seed 3 --full-cloud --camera-parent base_link
info="$(rosbag info "$dir/a.bag" 2>/dev/null)"
for topic in /thermal/image_raw /thermal/camera_info /thermal/human_mask /lidar/human_clusters /lidar/points /tf_static; do
  check "topic $topic present" grep -q "$topic" <<<"$info"
done
check "lz4 compression" grep -q "lz4" <<<"$info"
# /tf_static is stored latched, as rosbag record stores it, so rosbag play republishes it latched.
check "/tf_static is latched" /usr/bin/python3 -c "
import rosbag, sys
b = rosbag.Bag(sys.argv[1])
sys.exit(0 if any(c.topic == '/tf_static' and c.header.get('latching') in (b'1', '1')
                  for c in b._get_connections()) else 1)" "$dir/a.bag"
for key in lidar_frame camera_frame rotation_vector translation rotation_matrix quaternion_xyzw rig seed frames people; do
  check "truth key $key" grep -q "^$key:" "$dir/a.bag.truth.yaml"
done
check "truth frames" grep -q "^lidar_frame: velodyne" "$dir/a.bag.truth.yaml"

check "ms2, options" "$exe" --output "$dir/b.bag" --truth "$dir/b.yaml" --rig ms2 --frames 20 --noise realistic \
  --mask-style binary --image-encoding mono16 --no-camera-info --lidar-frame lidar --camera-frame cam --time-jitter-s 0.005
info="$(rosbag info "$dir/b.bag" 2>/dev/null)"
check "--no-camera-info omits camera_info" bash -c "! grep -q /thermal/camera_info <<<'$info'"
check "custom frames in truth" grep -q "^camera_frame: cam" "$dir/b.yaml"

"$exe" --output "$dir/c1.bag" --frames 15 --seed 5 >/dev/null 2>&1
"$exe" --output "$dir/c2.bag" --frames 15 --seed 5 >/dev/null 2>&1
check "same seed, byte-identical bag" cmp "$dir/c1.bag" "$dir/c2.bag"

echo "$failures failure(s)"
[ "$failures" -eq 0 ]
