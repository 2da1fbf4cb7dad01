#!/usr/bin/env bash
# The test suite on a fresh Debian 12 machine: installs what it needs (apt-get), builds the
# package and its tests, runs them (the unit and CLI tiers side by side, then the ROS tier), then
# prints "N passed, N failed, N skipped".
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
# cores; the CLI tests, the longest, first); the ROS tier then runs one test at a
# time (each rostest starts its own master on the same port). The time of each step goes to
# stderr; each test's time is in the JUnit files under
# .ws/build/test_results/thermal_lidar_calibration.
set -euo pipefail
steps=("run_cli_tests run_unit_tests" "run_ros_tests")
case "${1:-}" in
  "") ;;
  --fast) steps=("run_cli_tests run_unit_tests") ;;
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
mkdir -p "$ROS_HOME"
cd "$ws"
rm -rf "$ws/build/test_results/thermal_lidar_calibration"
jobs="${TLC_TEST_JOBS:-$(nproc)}"
times=""
for step in "${steps[@]}"; do
  step_jobs="$jobs"
  if [ "$step" = run_ros_tests ]; then step_jobs=1; fi
  SECONDS=0
  # A run_*_tests target never fails itself (catkin records each test's outcome); -k runs all.
  # shellcheck disable=SC2086  # $step holds make targets
  make -C "$ws/build" -k -j"$step_jobs" --output-sync=target $step >&2 || true
  times="$times${times:+; }${step//run_/} $((SECONDS / 60)) min $((SECONDS % 60)) s"
done
echo "run_tests: ${times//_tests/}" >&2
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
