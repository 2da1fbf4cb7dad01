#!/usr/bin/env bash
# Smoke test of the make_synthetic_bag CLI (no roscore): exit codes, topics, frame ids, truth keys.
# Usage: test/cli_synthetic/test_make_synthetic_bag.sh [PATH/TO/make_synthetic_bag]
# Registered in test/CMakeLists.txt (through run_as_junit.sh, so catkin counts it).
set -uo pipefail
export PATH=/usr/bin:/bin:$PATH
exe="${1:-make_synthetic_bag}"
dir="$(mktemp -d "${TLC_TEST_TMP:-/tmp}/tlc_synth_cli.XXXXXX")"
trap 'rm -rf "$dir"' EXIT
failures=0
check() {  # check DESCRIPTION COMMAND...
  local what="$1"; shift
  if "$@" >/dev/null 2>&1; then echo "ok   $what"; else echo "FAIL $what"; failures=$((failures + 1)); fi
}
exit_code() { "$exe" "$@" >/dev/null 2>"$dir/err"; echo $?; }

check "--help exits 0" "$exe" --help
for bad in "" "--output $dir/x.bag --frames 0" "--output $dir/x.bag --rig kitti" \
           "--output $dir/x.bag --no-such-flag" "--output $dir/x.bag --miss-rate 2" "--output $dir/x.bag --seed" \
           "--output $dir/x.bag --mask-edge-sign inward" "--output $dir/x.bag --mask-erosion-part legs"; do
  # shellcheck disable=SC2086
  code=$(exit_code $bad)
  check "bad arguments '$bad' exit 2 with one line" test "$code" = 2 -a "$(wc -l < "$dir/err")" = 1
done
# The drift and coverage options: each needs its partner or a valid value.
out="--output $dir/x.bag --frames 40"
for bad in "$out --extrinsic-change-at 2" "$out --extrinsic-change 0.5,3" \
           "$out --extrinsic-change-at 2 --extrinsic-change 0.5" "$out --extrinsic-change-at 2 --extrinsic-change 0,0" \
           "$out --extrinsic-change-at 2 --extrinsic-change a,3" "$out --extrinsic-change-at 2 --extrinsic-change 0.5,3,1" \
           "$out --extrinsic-change-at 2 --extrinsic-change 90,3" "$out --extrinsic-change-at 4 --extrinsic-change 0.5,3" \
           "$out --extrinsic-change-at -1 --extrinsic-change 0.5,3" "$out --empty-image-region top" \
           "$out --empty-image-region"; do
  # shellcheck disable=SC2086
  code=$(exit_code $bad)
  check "bad arguments '$bad' exit 2 with one line" test "$code" = 2 -a "$(wc -l < "$dir/err")" = 1
done
# The timing and drive options (issue 21): a bad value is one line naming the flag, exit 2.
for bad in "--camera-time-offset 0.6" "--camera-time-offset -0.51" "--camera-time-offset soon" \
           "--lidar-stamp middle" "--lidar-stamp" "--speed-profile fast" "--walking-fraction 1.5" \
           "--lidar-cut-azimuth 90" "--lidar-stamp end --lidar-cut-azimuth 400"; do
  # shellcheck disable=SC2086
  code=$(exit_code $out $bad)
  flag="${bad%% *}"
  [ "$bad" = "--lidar-stamp end --lidar-cut-azimuth 400" ] && flag=--lidar-cut-azimuth
  check "bad arguments '$bad' exit 2 with one line naming $flag" \
    test "$code" = 2 -a "$(wc -l < "$dir/err")" = 1 -a "$(grep -c -- "$flag" "$dir/err")" = 1
done
check "--help names the drift and region options" bash -c "'$exe' --help | grep -q -- '--extrinsic-change ROT_DEG,TRANS_CM' && '$exe' --help | grep -q -- '--empty-image-region'"

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
# Without timing flags: synchronised sensors, instantaneous scans, no time field, the steady drive.
check "truth: default timing" bash -c "grep -q '^time_offset_s: 0$' '$dir/a.bag.truth.yaml' && \
  grep -q '^lidar_stamp: instant$' '$dir/a.bag.truth.yaml' && grep -q '^speed_profile: steady$' '$dir/a.bag.truth.yaml'"
/usr/bin/python3 -c "
import rosbag, sys
for _, m, _ in rosbag.Bag(sys.argv[1]).read_messages(topics=['/lidar/points', '/lidar/human_clusters']):
    assert 'time' not in [f.name for f in m.fields]" "$dir/a.bag" >"$dir/no_time_check" 2>&1
check "no time field without --lidar-point-time" test "$(cat "$dir/no_time_check")" = ""

check "ms2, options" "$exe" --output "$dir/b.bag" --truth "$dir/b.yaml" --rig ms2 --frames 20 --noise realistic \
  --mask-style binary --image-encoding mono16 --no-camera-info --lidar-frame lidar --camera-frame cam --time-jitter-s 0.005
info="$(rosbag info "$dir/b.bag" 2>/dev/null)"
check "--no-camera-info omits camera_info" bash -c "! grep -q /thermal/camera_info <<<'$info'"
check "custom frames in truth" grep -q "^camera_frame: cam" "$dir/b.yaml"
check "the preset's mask edges move both ways" grep -q "^mask_edge_sign: both" "$dir/b.yaml"
check "eroded masks only" "$exe" --output "$dir/s.bag" --truth "$dir/s.yaml" --frames 5 --mask-edge-px 2 --mask-edge-sign shrink
check "the truth says which way the mask edges moved" grep -q "^mask_edge_sign: shrink" "$dir/s.yaml"
check "the preset's erosion takes all" grep -q "^mask_erosion_part: all" "$dir/s.yaml"
check "thin parts lost only" "$exe" --output "$dir/t.bag" --truth "$dir/t.yaml" --frames 5 --mask-edge-px 2 --mask-edge-sign shrink --mask-erosion-part thin
check "the truth says what the erosion took" grep -q "^mask_erosion_part: thin" "$dir/t.yaml"

# A bump 2 s into a 4 s drive: the truth keeps the start extrinsic at the top and adds the change.
check "extrinsic change bag" "$exe" --output "$dir/d.bag" --frames 40 --seed 3 --extrinsic-change-at 2 --extrinsic-change 0.5,3
check "truth: start extrinsic unchanged" cmp <(grep -E "^(rotation_vector|translation):" "$dir/a.bag.truth.yaml") \
  <(grep -E "^(rotation_vector|translation):" "$dir/d.bag.truth.yaml")
/usr/bin/python3 - "$dir/d.bag.truth.yaml" >"$dir/drift_check" 2>&1 <<'PY'
import math, sys, yaml
t = yaml.safe_load(open(sys.argv[1]))
c = t["extrinsic_change"]
assert abs(c["at_stamp"] - 1600000002.0) < 1e-6, c["at_stamp"]
assert c["rotation_deg"] == 0.5 and c["translation_cm"] == 3, c
assert abs(math.dist(c["after"]["translation"], t["translation"]) - 0.03) < 1e-9
for key in ("rotation_vector", "translation", "rotation_matrix", "quaternion_xyzw"):
    assert key in c["after"], key
assert abs(sum(a * a for a in c["axis"]) - 1.0) < 1e-9
PY
check "truth: extrinsic_change block (at_stamp, sizes, axis, after)" test "$(cat "$dir/drift_check")" = ""

# Left third empty: no mask pixel there in any frame, people elsewhere.
check "empty left region bag" "$exe" --output "$dir/e.bag" --frames 60 --seed 1 --empty-image-region left --noise realistic
check "truth: empty_image_region" grep -q "^empty_image_region: left" "$dir/e.bag.truth.yaml"
/usr/bin/python3 - "$dir/e.bag" >"$dir/region_check" 2>&1 <<'PY'
import rosbag, sys
inside = elsewhere = 0
for _, msg, _ in rosbag.Bag(sys.argv[1]).read_messages(topics=["/thermal/human_mask"]):
    third = (msg.width + 2) // 3  # columns u with u * 3 / width == 0
    for v in range(msg.height):
        row = msg.data[v * msg.step:v * msg.step + msg.width]
        inside += sum(1 for x in row[:third] if x)
        elsewhere += sum(1 for x in row[third:] if x)
assert inside == 0 and elsewhere > 0, (inside, elsewhere)
PY
check "empty left region: no mask pixel in the left third, some elsewhere" test "$(cat "$dir/region_check")" = ""

# --raw: what a vehicle records, for calibrate_bag --detect, with per-point person truth that
# agrees with the ideal clusters of the same frame.
check "raw bag" "$exe" --output "$dir/r.bag" --frames 30 --seed 2 --raw
/usr/bin/python3 - "$dir/r.bag" >"$dir/raw_check" 2>&1 <<'PY'
import rosbag, struct, sys
bag = rosbag.Bag(sys.argv[1])
images = [m for _, m, _ in bag.read_messages(topics=["/thermal/image_raw"])]
assert images and all(m.encoding == "mono16" for m in images), "image not mono16"
kelvin = [0.04 * struct.unpack_from("<H", images[0].data, 2 * i)[0] for i in range(0, images[0].width * images[0].height, 97)]
assert 250 < min(kelvin) and max(kelvin) < 320, (min(kelvin), max(kelvin))
person_frames = 0
for _, cloud, t in bag.read_messages(topics=["/lidar/points"]):
    names = [f.name for f in cloud.fields]
    assert names == ["x", "y", "z", "intensity", "ring", "truth_id"], names
    assert cloud.width > 20000, cloud.width
    ids = set()
    for i in range(cloud.width):
        ring, truth = struct.unpack_from("<HI", cloud.data, i * cloud.point_step + 16)
        assert ring < 32, ring
        if truth:
            ids.add(truth)
    person_frames += bool(ids)
assert person_frames > 0, "no person point in any scan"
# The per-pixel truth holds the same person ids as the per-point truth.
pixel_ids = set()
for _, ids, _ in bag.read_messages(topics=["/truth/thermal_person_ids"]):
    assert ids.encoding == "mono16", ids.encoding
    for i in range(0, ids.width * ids.height, 7):
        v = struct.unpack_from("<H", ids.data, 2 * i)[0]
        if v:
            pixel_ids.add(v)
point_ids = set()
for _, cloud, _ in bag.read_messages(topics=["/lidar/points"]):
    for i in range(0, cloud.width, 5):
        truth = struct.unpack_from("<I", cloud.data, i * cloud.point_step + 18)[0]
        if truth:
            point_ids.add(truth)
assert pixel_ids and pixel_ids & point_ids, (sorted(pixel_ids), sorted(point_ids))
PY
check "raw bag: mono16 kelvin range, full clouds with ring and truth_id, people in them" test "$(cat "$dir/raw_check")" = ""

# Issue 21: a late camera, a swept scan stamped at its end with velodyne's float32 `time`, the
# field drive; the truth says how the clocks were.
check "timed field bag" "$exe" --output "$dir/t.bag" --frames 40 --seed 3 --full-cloud --lidar-point-time \
  --camera-time-offset 0.06 --speed-profile field --walking-fraction 1
check "timed raw bag" "$exe" --output "$dir/tr.bag" --frames 10 --seed 3 --raw --lidar-point-time --lidar-stamp start
check "swept bag without the time field" "$exe" --output "$dir/ts.bag" --frames 10 --seed 3 --full-cloud --lidar-stamp start
/usr/bin/python3 - "$dir" >"$dir/time_check" 2>&1 <<'PY'
import rosbag, struct, sys, yaml
d = sys.argv[1]
FLOAT32 = 7
def times(msg):
    f = {x.name: x for x in msg.fields}
    assert f["time"].datatype == FLOAT32 and f["time"].count == 1, f["time"]
    return [struct.unpack_from("<f", msg.data, i * msg.point_step + f["time"].offset)[0] for i in range(msg.width)]
seen = {"/lidar/points": 0, "/lidar/human_clusters": 0}
for topic, msg, _ in rosbag.Bag(d + "/t.bag").read_messages(topics=list(seen)):
    names = [x.name for x in msg.fields]
    expected = ["x", "y", "z", "label", "time"] if topic == "/lidar/human_clusters" else ["x", "y", "z", "intensity", "time"]
    assert names == expected, (topic, names)
    t = times(msg)
    assert all(-0.1 <= v <= 0.0 for v in t), (topic, min(t), max(t))
    seen[topic] += len(t)
assert seen["/lidar/points"] > 1000 and seen["/lidar/human_clusters"] > 0, seen
for _, msg, _ in rosbag.Bag(d + "/tr.bag").read_messages(topics=["/lidar/points"]):
    assert [x.name for x in msg.fields] == ["x", "y", "z", "intensity", "ring", "truth_id", "time"]
    t = times(msg)
    assert 0.0 <= min(t) and max(t) < 0.1 and max(t) - min(t) > 0.09, (min(t), max(t))
for _, msg, _ in rosbag.Bag(d + "/ts.bag").read_messages(topics=["/lidar/points"]):
    assert "time" not in [x.name for x in msg.fields]
t = yaml.safe_load(open(d + "/t.bag.truth.yaml"))
assert t["time_offset_s"] == 0.06 and t["lidar_stamp"] == "end" and t["lidar_point_time"] is True, t
assert t["speed_profile"] == "field" and t["walking_fraction"] == 1 and t["lidar_sweep_period_s"] == 0.1, t
assert abs(t["camera_axis_scan_time_s"] + 0.05) < 0.002, t["camera_axis_scan_time_s"]
assert abs(t["time_offset_at_scan_stamp_s"] - 0.06 + t["camera_axis_scan_time_s"]) < 1e-12
s = yaml.safe_load(open(d + "/ts.bag.truth.yaml"))
assert s["lidar_stamp"] == "start" and s["lidar_point_time"] is False, s
PY
check "time field on points and clusters (float32, within the sweep), truth timing keys" test "$(cat "$dir/time_check")" = ""
check "--help names the timing options" bash -c "'$exe' --help | grep -q -- '--camera-time-offset S' && '$exe' --help | grep -q -- '--speed-profile'"

"$exe" --output "$dir/c1.bag" --frames 15 --seed 5 >/dev/null 2>&1
"$exe" --output "$dir/c2.bag" --frames 15 --seed 5 >/dev/null 2>&1
check "same seed, byte-identical bag" cmp "$dir/c1.bag" "$dir/c2.bag"

echo "$failures failure(s)"
[ "$failures" -eq 0 ]
