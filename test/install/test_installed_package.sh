#!/usr/bin/env bash
# The installed package works on its own: installs the built workspace into a fresh prefix
# (what `catkin_make install` does), then, in an environment that knows only that prefix and
# /usr, runs the demo (make_synthetic_bag + calibrate_bag with --truth) and starts
# calibration_node and the calibration nodelet, each until it publishes ~status.
# Usage: test_installed_package.sh WORKSPACE_BUILD_DIR
set -euo pipefail
export PATH=/usr/bin:/bin:/usr/sbin:/sbin:$PATH
build_dir="$1"
work="$(mktemp -d "${TLC_TEST_TMP:-/tmp}/tlc_install_XXXXXX")"
master_pid=""
stop() {  # PID: SIGINT as Ctrl-C would, SIGKILL if it is still there after 15 s
  kill -INT "$1" 2>/dev/null || return 0
  for _ in $(seq 1 150); do kill -0 "$1" 2>/dev/null || break; sleep 0.1; done
  kill -KILL "$1" 2>/dev/null || true
  wait "$1" 2>/dev/null || true
}
cleanup() {
  if [ -n "$master_pid" ]; then stop "$master_pid"; fi
  rm -rf "$work"
}
trap cleanup EXIT

prefix="$work/install"
echo "== installing into $prefix"
cmake -DCMAKE_INSTALL_PREFIX="$prefix" -P "$build_dir/cmake_install.cmake" >"$work/install.log"
# catkin writes its setup files to the configured prefix by absolute path; they locate
# themselves, so the generated ones are copied (catkin_make install puts the same files there).
cp "$build_dir"/catkin_generated/installspace/{_setup_util.py,env.sh,setup.*,local_setup.*} "$prefix/"
share="$prefix/share/thermal_lidar_calibration"
for f in "$share/package.xml" "$share/nodelet_plugins.xml" "$share/launch/calibration.launch" \
         "$share/config/default.yaml" "$share/rviz/calibration.rviz" "$share/msg/CalibrationStatus.msg" \
         "$prefix/include/thermal_lidar_calibration/app/parameters/core_parameters.hpp" \
         "$prefix/lib/libthermal_lidar_calibration_nodelets.so"; do
  [ -e "$f" ] || { echo "FAIL: not installed: $f"; exit 1; }
done

# A clean environment: nothing of the devel space or the source tree.
in_install() {
  env -i HOME="$work" PATH=/usr/bin:/bin ROS_HOME="$work/ros_home" ROS_LOG_DIR="$work/log" \
    ROS_MASTER_URI="http://localhost:$port" bash -c "set +u; source '$prefix/setup.bash'; set -u; $1"
}
# The same in the background; `exec` all the way down, so $! is the process itself.
start_in_install() {  # LOG COMMAND
  env -i HOME="$work" PATH=/usr/bin:/bin ROS_HOME="$work/ros_home" ROS_LOG_DIR="$work/log" \
    ROS_MASTER_URI="http://localhost:$port" \
    bash -c "set +u; source '$prefix/setup.bash'; set -u; exec $2" >"$1" 2>&1 &
}
port=$((20000 + RANDOM % 20000))

found="$(in_install 'rospack find thermal_lidar_calibration')"
[ "$found" = "$share" ] || { echo "FAIL: rospack finds the package at $found, not $share"; exit 1; }
for lib in lib/thermal_lidar_calibration/calibrate_bag lib/thermal_lidar_calibration/calibration_node \
           lib/thermal_lidar_calibration/make_synthetic_bag lib/libthermal_lidar_calibration_nodelets.so; do
  libs="$(in_install "ldd '$prefix/$lib'")"
  if echo "$libs" | grep -q 'not found'; then
    echo "FAIL: $lib does not find its libraries:"; echo "$libs" | grep 'not found'; exit 1
  fi
  if echo "$libs" | grep thermal_lidar_calibration | grep -v -q "=> $prefix/"; then
    echo "FAIL: $lib links a library outside the install space:"; echo "$libs" | grep thermal_lidar; exit 1
  fi
done
in_install 'rospack plugins --attrib=plugin nodelet' | grep -q "$share/nodelet_plugins.xml" \
  || { echo "FAIL: the nodelet plugin description is not exported"; exit 1; }

echo "== what catkin_package exports, used by a downstream program"
config="$share/cmake/thermal_lidar_calibrationConfig.cmake"
for lib in core app synthetic ros; do
  grep -q "set(libraries \".*thermal_lidar_calibration_$lib[;\"]" "$config" \
    || { echo "FAIL: catkin_package does not export thermal_lidar_calibration_$lib"; exit 1; }
done
grep -q '_include_dirs ".*eigen3' "$config" || { echo "FAIL: catkin_package does not export Eigen"; exit 1; }
cat >"$work/downstream.cpp" <<'CPP'
#include <thermal_lidar_calibration/app/parameters/core_parameters.hpp>
#include <iostream>
int main(int, char** argv) {
  namespace tlc = thermal_lidar_calibration;
  const auto p = tlc::loadCoreParameters(*tlc::makeYamlParameterSource(argv[1]));
  std::cout << p.calibration.evolution.population_size << "\n";
}
CPP
g++ -std=c++17 -o "$work/downstream" "$work/downstream.cpp" -I"$prefix/include" -I/usr/include/eigen3 \
  -I/usr/include/opencv4 -L"$prefix/lib" -lthermal_lidar_calibration_app -lthermal_lidar_calibration_core
[ "$(in_install "'$work/downstream' '$share/config/default.yaml'")" = 500 ] \
  || { echo "FAIL: a program built on the installed headers and libraries does not run"; exit 1; }

echo "== the demo from the install space"
in_install "rosrun thermal_lidar_calibration make_synthetic_bag --output '$work/demo.bag' --truth '$work/truth.yaml' --seed 1"
in_install "rosrun thermal_lidar_calibration calibrate_bag --bag '$work/demo.bag' --output '$work/result.yaml' --truth '$work/truth.yaml' --threads 2"
rot="$(awk '/rotation_error_deg:/ {print $2}' "$work/result.yaml")"
trans="$(awk '/translation_error_m:/ {print $2}' "$work/result.yaml")"
echo "demo from the install space: rotation error $rot deg, translation error $trans m"
awk -v r="$rot" -v t="$trans" 'BEGIN { exit !(r != "" && t != "" && r < 0.1 && t < 0.02) }' \
  || { echo "FAIL: the installed calibrate_bag missed the truth (demo: 0.02 deg / 0.6 cm)"; exit 1; }

echo "== calibration_node and the nodelet from the install space"
start_in_install "$work/roscore.log" "roscore -p $port"
master_pid=$!
in_install "for i in \$(seq 1 100); do rostopic list >/dev/null 2>&1 && exit 0; sleep 0.2; done; exit 1" \
  || { echo "FAIL: roscore did not start"; cat "$work/roscore.log"; exit 1; }
status_of() {  # NAME COMMAND: start COMMAND, wait for NAME/status, stop it
  start_in_install "$work/$1.log" "$2"
  local pid=$!
  local ok=0
  in_install "timeout 60 rostopic echo -n 1 /$1/status/state_name" >"$work/$1.status" 2>&1 || ok=$?
  stop "$pid"
  if [ "$ok" -ne 0 ] || ! grep -q collecting "$work/$1.status"; then
    echo "FAIL: /$1 published no ~status"; cat "$work/$1.log" "$work/$1.status"; exit 1
  fi
  echo "/$1: ~status says $(grep -m1 collecting "$work/$1.status")"
}
args="_camera_info_file:=$share/config/flir_a65_camera_info.yaml _dataset_bag:=$work/dataset.bag"
status_of installed_node "rosrun thermal_lidar_calibration calibration_node __name:=installed_node $args"
status_of installed_nodelet "rosrun nodelet nodelet standalone thermal_lidar_calibration/CalibrationNodelet __name:=installed_nodelet $args"
echo "PASS: the installed package runs"
