#!/usr/bin/env bash
# launch-prefix for a node that needs a file another test node writes first (the generator's
# truth file): waits up to 120 s for FILE, then runs the node's command.
# Usage (in a .test file): launch-prefix="$(find thermal_lidar_calibration)/test/ros/wait_for_file.sh FILE"
file="$1"; shift
for _ in $(seq 1 1200); do
  [ -s "$file" ] && exec "$@"
  sleep 0.1
done
echo "wait_for_file.sh: $file did not appear in 120 s" >&2
exit 1
