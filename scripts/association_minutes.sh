#!/usr/bin/env bash
# Minutes of driving until calibration_node's verdict is first `good` (~stop_when: quality), with
# pairing counts and pairing association on the same drives (issue 23). For each seed a
# FieldSAFE-like drive (make_synthetic_bag --speed-profile field --walking-fraction 0.5: stops,
# turns and walkers, so that the camera's time offset can be told at all) is played to the node by
# paced_bag_player --hold-while-optimizing: the node sees every frame and nothing is sent while it
# fits, so the figures are the data's, not the machine's. With --raw the drive is raw
# (--raw --noise realistic) and goes through the two detector nodelets first (detection.launch).
# The node runs the default parameters with stop_when quality; it fits at pairs_required and again
# every quality_check_every_pairs count-rule pairs until the verdict is good or max_pairs.
# One row per run: seed, pairing, fits, verdict at the end, count / association pairs of the
# last fit, and the minutes of driving up to the last pair of the first good fit ("never" when
# the drive ended first, with its length), and the last fit's signed error against the truth
# (rotation about the camera's x, y, z: the rotation vector of R_result R_truth^T; translation
# along them; result minus truth).
# Usage: scripts/association_minutes.sh [--raw] [--frames N] [SEEDS...]   (default 3000 frames = 5 min)
# (TLC_MINUTES_PAIRINGS="association" runs one pairing only.) Results under out/association_minutes
# (TLC_MINUTES_OUT); play_synthetic_bag.sh caches the drives in ${TLC_TEST_TMP:-/tmp}/tlc_bag_cache
# (about 2 GB per raw drive: delete them after use).
set -euo pipefail
export PATH=/usr/bin:/bin:/usr/sbin:/sbin:$PATH
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
ws="${TLC_WS:-$repo/.ws}"
raw=0
frames=3000
seeds=()
while [ $# -gt 0 ]; do
  case "$1" in
    --raw) raw=1; shift ;;
    --frames) frames="$2"; shift 2 ;;
    *) seeds+=("$1"); shift ;;
  esac
done
[ ${#seeds[@]} -gt 0 ] || seeds=(1 2 3)
set +u
# shellcheck disable=SC1091
source "$ws/devel/setup.bash"
set -u
out="${TLC_MINUTES_OUT:-$repo/out/association_minutes}"
mkdir -p "$out"
port="${TLC_MINUTES_PORT:-11651}"  # a master of its own, apart from any rostest's
export ROS_MASTER_URI="http://localhost:$port" ROS_HOME="$out/ros_home"
mkdir -p "$ROS_HOME"
gen=(--seed SEED --frames "$frames" --speed-profile field --walking-fraction 0.5)
[ "$raw" = 1 ] && gen+=(--raw --noise realistic)
tag="$([ "$raw" = 1 ] && echo raw || echo ideal)"

launch_file() {  # WORK_DIR PAIRING SEED
  local player_args="--hold-while-optimizing" detect=""
  local remap=""
  if [ "$raw" = 1 ]; then
    player_args="--detectors --window 2 --hold-while-optimizing"
    # shellcheck disable=SC2016  # $(find ...) is roslaunch's, not the shell's
    detect='<include file="$(find thermal_lidar_calibration)/launch/detection.launch">
    <arg name="image_topic" value="/thermal/image_raw"/><arg name="points_topic" value="/lidar/points"/>
    <arg name="mask_topic" value="/detected/human_mask"/><arg name="clusters_topic" value="/detected/human_clusters"/>
  </include>'
    remap='<remap from="thermal/human_mask" to="/detected/human_mask"/>
    <remap from="lidar/human_clusters" to="/detected/human_clusters"/>'
  fi
  cat <<EOF
<launch>
  <param name="/use_sim_time" value="true"/>
  <node pkg="thermal_lidar_calibration" type="play_synthetic_bag.sh" name="player" output="log"
        args="$1 $player_args -- ${gen[*]/SEED/$3}"/>
  $detect
  <node pkg="thermal_lidar_calibration" type="calibration_node" name="calibration_node" output="log">
    <rosparam command="load" file="\$(find thermal_lidar_calibration)/config/default.yaml"/>
    <param name="stop_when" value="quality"/>
    <param name="pairing" value="$2"/>
    <param name="output_file" value="$1/result.yaml"/>
    <param name="dataset_bag" value=""/>
    <param name="status_rate_hz" value="20.0"/>
    $remap
  </node>
</launch>
EOF
}

# Waits until the node is done, or the player has played everything and the node has been
# collecting (not fitting) for 20 status messages in a row; prints fits and the final state.
wait_done() {
  /usr/bin/python3 - <<'PY'
import rospy
from std_msgs.msg import UInt32
from thermal_lidar_calibration.msg import CalibrationStatus
s = {"fits": 0, "state": "", "player_done": False, "idle": 0}
def on_status(m):
    if m.state_name == "optimizing" and s["state"] != "optimizing":
        s["fits"] += 1
    s["state"] = m.state_name
    s["idle"] = s["idle"] + 1 if (s["player_done"] and m.state_name == "collecting") else 0
def on_done(m):
    s["player_done"] = True
rospy.init_node("minutes_watch", anonymous=True)
rospy.Subscriber("/calibration_node/status", CalibrationStatus, on_status, queue_size=100)
rospy.Subscriber("/player/done", UInt32, on_done)
while not rospy.is_shutdown() and s["state"] != "done" and s["idle"] < 20:
    rospy.sleep(0.2)
print(s["fits"], s["state"])
PY
}

row() {  # RESULT TRUTH SEED PAIRING FITS STATE BAG
  PYTHONPATH="$repo/scripts" /usr/bin/python3 - "$@" <<'PY'
import math, subprocess, sys, yaml
from extrinsic_error import signed_error
res, truth, seed, pairing, fits, state, bag = sys.argv[1:8]
info = yaml.safe_load(subprocess.run(["rosbag", "info", "--yaml", bag], capture_output=True, text=True).stdout)
start, end = float(info["start"]), float(info["end"])
drive = "never (%.1f min drive)" % ((end - start) / 60)
try:
    r, t = yaml.safe_load(open(res)), yaml.safe_load(open(truth))
except OSError:
    print("| %s | %s | %s | no result | - | - | - | - | %s |" % (seed, pairing, fits, drive)); sys.exit()
a, w, dt = signed_error(r, t)
w = [math.degrees(x) for x in w]
by = r["pairs_by_rule"]
last = max(p["stamp"] for p in r["pairs"])
good = r["verdict"] == "good" and state == "done"
minutes = "%.2f" % ((last - start) / 60) if good else drive
print("| %s | %s | %s | %s | %d | %d | %s | %s | %s |" % (
    seed, pairing, fits, r["verdict"], by["counts"], by["association"],
    " ".join("%+.3f" % x for x in w), " ".join("%+.2f" % x for x in dt), minutes))
PY
}

echo "| seed | pairing | fits | verdict at the end | counts pairs | association pairs | rotation error deg (x y z) | translation error cm (x y z) | minutes until good |"
echo "|---|---|---|---|---|---|---|---|---|"
for seed in "${seeds[@]}"; do
  for pairing in ${TLC_MINUTES_PAIRINGS:-counts association}; do
    work="$out/$tag.$seed.$pairing"
    launch_file "$work" "$pairing" "$seed" > "$out/$tag.$seed.$pairing.launch"
    roslaunch -p "$port" "$out/$tag.$seed.$pairing.launch" > "$out/$tag.$seed.$pairing.log" 2>&1 &
    launch_pid=$!
    # The watcher's last line (rospy may print to stdout before it).
    result="$( (timeout 7200 bash -c "$(declare -f wait_done); wait_done" || echo "0 timeout") | tail -n 1)"
    kill -INT "$launch_pid" 2>/dev/null || true
    wait "$launch_pid" 2>/dev/null || true
    # shellcheck disable=SC2086
    row "$work/result.yaml" "$work/truth.yaml" "$seed" "$pairing" $result "$work/synthetic.bag"
  done
done
