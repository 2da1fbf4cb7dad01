#!/usr/bin/env bash
# Installs Debian 12's own ROS 1 packages and the tools this package builds with.
# Idempotent and quick when everything is already there (checks with dpkg first).
set -euo pipefail
export PATH=/usr/bin:/bin:/usr/sbin:/sbin:$PATH

packages=(
  build-essential cmake ros-core-dev catkin libroscpp-dev librosbag-dev libroslz4-dev libsensor-msgs-dev
  libgeometry-msgs-dev libstd-srvs-dev libtf2-ros-dev libtf2-msgs-dev libcv-bridge-dev
  libimage-transport-dev libmessage-filters-dev libopencv-dev libeigen3-dev libyaml-cpp-dev
  python3-rostest librostest-dev ros-message-generation ros-message-runtime rosbash
  googletest libgtest-dev libbenchmark-dev python3-rosbag python3-yaml python3-std-srvs python3-sensor-msgs
  libpcl-dev libpcl-conversions-dev libnodeletlib-dev libnodeletlib-tools
  libdiagnostic-updater-dev libdiagnostic-msgs-dev libvisualization-msgs-dev
  rviz tf2-tools
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "[install_deps] installing: ${missing[*]}" >&2
  SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
echo "[install_deps] all dependencies present" >&2
