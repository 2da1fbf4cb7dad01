#!/usr/bin/env bash
# CPU of calibration_node in monitor mode (issue 9: under 10 % of one core at sensor rate): a
# synthetic drive (ideal masks and clusters, 10 Hz) played at 1x, the node watching the truth's
# extrinsic (~mode: monitor, ~reference_file), ~overlay not watched. CPU is read from
# /proc/<pid>/stat (utime + stime) over the playback and printed as % of one core, with the
# drift watch's own share from ~status.
# Usage: scripts/monitor_cpu.sh [FRAMES]   (default 1200: a 120 s drive, 120 s of playback)
set -euo pipefail
# shellcheck source=scripts/workspace.sh
source "$(dirname "${BASH_SOURCE[0]}")/workspace.sh"
prepare_workspace
frames="${1:-1200}"
out="${TLC_ACCURACY_OUT:-$repo/out/monitor_cpu}"
mkdir -p "$out"
"$bin/make_synthetic_bag" --frames "$frames" --seed 3 --noise realistic --output "$out/drive.bag" \
  --truth "$out/truth.yaml" >/dev/null 2>&1
start_private_roscore "$out" 11398
trap 'kill $node_pid $roscore_pid 2>/dev/null || true; wait 2>/dev/null || true' EXIT
rosparam set /use_sim_time true
rosparam load "$repo/config/default.yaml" /calibration_node
rosparam set /calibration_node/mode monitor
rosparam set /calibration_node/reference_file "$out/truth.yaml"
rosparam set /calibration_node/output_file "$out/result.yaml"
"$bin/calibration_node" >"$out/node.log" 2>&1 &
node_pid=$!
sleep 3
hz=$(getconf CLK_TCK)
n0=$(cpu_ticks "$node_pid"); t0=$(date +%s.%N)
rosbag play --clock -q "$out/drive.bag"
n1=$(cpu_ticks "$node_pid"); t1=$(date +%s.%N)
sleep 1
status="$(timeout 10 rostopic echo -n 1 /calibration_node/status)"
tests=$(echo "$status" | awk '/^drift_tests:/ {print $2}')
state=$(echo "$status" | awk '/^drift_state:/ {print $2}')
seen=$(echo "$status" | awk '/^drift_pairs_seen:/ {print $2}')
awk -v n="$((n1 - n0))" -v t0="$t0" -v t1="$t1" -v hz="$hz" -v f="$frames" -v tests="$tests" \
    -v state="$state" -v seen="$seen" 'BEGIN {
  s = t1 - t0
  printf "%d frames at 1x (10 Hz) in %.1f s: calibration_node in monitor mode %.1f %% of one core\n",
         f, s, 100 * n / hz / s
  printf "  (%s kept pairs watched, %s window tests, drift state %s at the end)\n", seen, tests, state
}'
rm -f "$out/drive.bag"
