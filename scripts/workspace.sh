# Sourced by the scripts in this folder (not run on its own). Defines prepare_workspace, which
# installs the dependencies, builds the package in its catkin workspace and sources it, leaving
# the workspace path in $ws, the package's executables in $bin and the checkout in $repo.
#   prepare_workspace            build the package
#   prepare_workspace --tests    also build the tests (--bench: the benchmarks)
# and, for the CPU measurements, start_private_roscore and cpu_ticks (below).
# Debian's ROS tools need Debian's python3, not a pyenv one that may be first on PATH.
export PATH=/usr/bin:/bin:/usr/sbin:/sbin:$PATH
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

prepare_workspace() {
  bash "$repo/scripts/install_deps.sh"
  ws="$(bash "$repo/scripts/build.sh" "$@" | tail -n 1)"
  # $bin is for the scripts that source this file.
  # shellcheck disable=SC2034
  bin="$ws/devel/lib/thermal_lidar_calibration"
  # Debian's catkin profile hooks read unset variables: source them without -u.
  set +u
  # shellcheck disable=SC1091
  source "$ws/devel/setup.bash"
  set -u
}

# TLC_BIN set: run those already built executables (a copy, so that a rebuild cannot change them
# mid-run) as $bin; otherwise prepare_workspace with these arguments.
prepare_workspace_unless_bin() {
  # shellcheck disable=SC2034  # $bin is for the scripts that source this file
  if [ -n "${TLC_BIN:-}" ]; then bin="$TLC_BIN"; else prepare_workspace "$@"; fi
}

# For the CPU measurements: a roscore of the script's own on PORT (so it never meets another
# master), ROS_HOME and its log under DIR; its PID in $roscore_pid for the caller's exit trap.
start_private_roscore() {  # DIR PORT
  export ROS_HOME="$1/ros_home" ROS_MASTER_URI="http://localhost:$2"
  mkdir -p "$ROS_HOME"
  roscore -p "$2" >"$1/roscore.log" 2>&1 &
  # shellcheck disable=SC2034  # for the caller's trap
  roscore_pid=$!
  sleep 3
}

# CPU time a process has used so far, in clock ticks (user + system; $(getconf CLK_TCK) a second).
cpu_ticks() { awk '{print $14 + $15}' "/proc/$1/stat"; }
