#!/usr/bin/env bash
# The whole test suite on a fresh Debian 12 machine: installs what it needs (apt-get), builds
# the package and its tests, runs the core gtests, the ROS-side gtests, the calibrate_bag CLI
# tests and the calibration_node rostests, then prints "N passed, N failed".
set -euo pipefail
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
mkdir -p "$ROS_HOME"
cd "$ws"
rm -rf "$ws/build/test_results/thermal_lidar_calibration"
# One job: the rostests start their own masters and the machine has two cores.
catkin_make run_tests -j1 >&2 || true
summary="$(catkin_test_results build/test_results --verbose 2>&1 || true)"
echo "$summary" | grep -E "^(Summary|.*\.xml: [0-9]+ tests)|failure|error" | grep -v ", 0 errors, 0 failures" >&2 || true
line="$(echo "$summary" | grep -E '^Summary: ' | tail -n 1)"
if [ -z "$line" ]; then
  echo "run_tests: no test results were produced (see the build output above)" >&2
  echo "0 passed, 1 failed"
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
