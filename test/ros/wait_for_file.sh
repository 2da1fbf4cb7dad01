#!/usr/bin/env bash
# launch-prefix for a node that needs a file another test node writes first (the generator's
# truth file): waits up to 120 s for FILE, written at most 5 s before this script started, then
# runs the node's command. A FILE left over from an earlier run of the same test (a reused work
# directory) is older than that and does not count: the generator replaces it.
# Usage (in a .test file): launch-prefix="$(find thermal_lidar_calibration)/test/ros/wait_for_file.sh FILE"
file="$1"; shift
started="$(mktemp)"
trap 'rm -f "$started"' EXIT
touch -d "@$(( $(date +%s) - 5 ))" "$started"
for _ in $(seq 1 1200); do
  if [ -s "$file" ] && [ "$file" -nt "$started" ]; then
    rm -f "$started"
    exec "$@"
  fi
  sleep 0.1
done
echo "wait_for_file.sh: $file was not written in 120 s" >&2
exit 1
