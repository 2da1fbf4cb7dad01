#!/usr/bin/env bash
# Builds the package in a catkin workspace (default: .ws/ inside the checkout, or $TLC_WS) whose
# src/ holds a symlink to this repository. Prints the workspace path on the last line.
# Usage: scripts/build.sh [--tests] [--bench]
#   --tests  also builds the gtest/rostest targets
#   --bench  also builds the benchmarks, score_raw_detections, score_association and score_motion (bench/)
set -euo pipefail
# shellcheck source=scripts/workspace.sh
source "$(dirname "${BASH_SOURCE[0]}")/workspace.sh"  # PATH and $repo
ws="${TLC_WS:-$repo/.ws}"
mkdir -p "$ws/src"
ln -sfn "$repo" "$ws/src/thermal_lidar_calibration"
jobs="${TLC_JOBS:-$(nproc)}"
# ccache, when the machine has it, makes a rebuild after a small change, or in a second checkout
# (CI's fresh clone), take seconds instead of minutes. With the workspace inside the checkout,
# the checkout is ccache's base directory: every path it sees is then the same relative to the
# build folder in any clone, wherever it lies. The sloppiness lets it cache the files compiled
# with a precompiled header (cmake/precompiled_headers.cmake).
launcher=()
if command -v ccache >/dev/null; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  case "$ws/" in "$repo"/*) export CCACHE_BASEDIR="$repo" ;; esac
  export CCACHE_SLOPPINESS="${CCACHE_SLOPPINESS:-pch_defines,time_macros,include_file_mtime,include_file_ctime}"
fi
cd "$ws"
catkin_make -DCMAKE_BUILD_TYPE=Release -DCATKIN_ENABLE_TESTING=ON "${launcher[@]}" -j"$jobs" >&2
for extra in "$@"; do
  case "$extra" in
    --tests) catkin_make tests -j"$jobs" >&2 ;;
    --bench) catkin_make benchmarks -j"$jobs" >&2 ;;
    *) echo "usage: scripts/build.sh [--tests] [--bench]" >&2; exit 2 ;;
  esac
done
echo "$ws"
