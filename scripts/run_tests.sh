#!/usr/bin/env bash
# The test suite on a fresh Debian 12 machine: installs what it needs (apt-get), builds the
# package and its tests, runs them (the unit and CLI tiers side by side, the ROS tier beside
# them), then prints "N passed, N failed, N skipped".
#
# Usage: scripts/run_tests.sh [--fast]
#   (none)   every tier: unit, CLI and ROS (CI runs this, through .ci/run)
#   --fast   the unit and CLI tiers only, for day-to-day work
# The tiers (test/tiers.cmake puts each test in one, from how it is registered):
#   unit  the libraries' gtests and the static checks (launch files, the ROS-free boundary):
#         nothing is started, no ROS master
#   cli   calibrate_bag, detect_people and make_synthetic_bag end to end, on files they write
#   ros   the calibration_node rostests and the installed package: a ROS master and nodes
# The unit and CLI tiers run together, TLC_TEST_JOBS tests at a time (default: the machine's
# cores; the CLI tests, the longest, first); the ROS tier runs beside them, one test at a time
# (its tests start nodes that keep about one core busy, and the other tiers fill both: run one
# after the other they left a core idle for four minutes). Every test waits on state, not on
# time, so each holds on a loaded machine. The time of each tier goes to stderr; each test's time
# is in the JUnit files under .ws/build/test_results/thermal_lidar_calibration.
set -euo pipefail
with_ros=1
case "${1:-}" in
  "") ;;
  --fast) with_ros=0 ;;
  *) echo "usage: scripts/run_tests.sh [--fast]" >&2; exit 2 ;;
esac
# shellcheck source=scripts/workspace.sh
source "$(dirname "${BASH_SOURCE[0]}")/workspace.sh"
prepare_workspace --tests
# Every test writes its files under one directory: removed after a green run, kept and named
# after a red one (set TLC_TEST_TMP to choose it; a directory you choose is never removed).
own_tmp=""
if [ -z "${TLC_TEST_TMP:-}" ]; then
  TLC_TEST_TMP="$(mktemp -d /tmp/tlc_tests.XXXXXX)"
  own_tmp=1
fi
export TLC_TEST_TMP
export ROS_HOME="${ROS_HOME:-$ws/ros_home}"
# Three tests at a time on two cores: OpenMP's threads must sleep, not spin, between parallel
# regions (the launch files ask the same of the node). Spinning, the suite took 18 CPU minutes
# instead of 12, and 10 minutes instead of 6.5 (docs/validation/performance.md).
export OMP_WAIT_POLICY="${OMP_WAIT_POLICY:-PASSIVE}"
mkdir -p "$ROS_HOME"
cd "$ws"
rm -rf "$ws/build/test_results/thermal_lidar_calibration"
jobs="${TLC_TEST_JOBS:-$(nproc)}"
# One tier (make targets): its time goes to $times_dir/<name>. A run_*_tests target never fails
# itself (catkin records each test's outcome); -k runs all.
times_dir="$(mktemp -d)"
run_tier() {  # name jobs targets...
  local name=$1 tier_jobs=$2 start=$SECONDS
  shift 2
  make -C "$ws/build" -k -j"$tier_jobs" --output-sync=target "$@" >&2 || true
  local took=$((SECONDS - start))
  echo "$name $((took / 60)) min $((took % 60)) s" > "$times_dir/$name"
}
ros_pid=""
if [ "$with_ros" = 1 ]; then
  run_tier ros 1 run_ros_tests &
  ros_pid=$!
fi
run_tier "cli unit" "$jobs" run_cli_tests run_unit_tests
if [ -n "$ros_pid" ]; then wait "$ros_pid" || true; fi
echo "run_tests: $(cat "$times_dir"/* | paste -sd ';' | sed 's/;/; /g')" >&2
rm -rf "$times_dir"
summary="$(catkin_test_results build/test_results --verbose 2>&1 || true)"
echo "$summary" | grep -E "^(Summary|.*\.xml: [0-9]+ tests)|failure|error" | grep -v ", 0 errors, 0 failures" >&2 || true
line="$(echo "$summary" | grep -E '^Summary: ' | tail -n 1)"
if [ -z "$line" ]; then
  echo "run_tests: no test results were produced (see the build output above)" >&2
  echo "0 passed, 1 failed, 0 skipped"
  exit 1
fi
tests=$(echo "$line" | sed -E 's/^Summary: ([0-9]+) tests.*/\1/')
errors=$(echo "$line" | sed -E 's/.* ([0-9]+) errors.*/\1/')
failures=$(echo "$line" | sed -E 's/.* ([0-9]+) failures.*/\1/')
skipped=$(echo "$line" | sed -E 's/.* ([0-9]+) skipped.*/\1/')
failed=$((errors + failures))
passed=$((tests - failed - skipped))
echo "$line" >&2
if [ -n "$own_tmp" ]; then
  if [ "$failed" -eq 0 ]; then rm -rf "$TLC_TEST_TMP"; else echo "test files kept in $TLC_TEST_TMP" >&2; fi
fi
echo "${passed} passed, ${failed} failed, ${skipped} skipped"
[ "$failed" -eq 0 ] && [ "$tests" -gt 0 ]
