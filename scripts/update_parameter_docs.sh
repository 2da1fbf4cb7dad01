#!/usr/bin/env bash
# Rewrites config/default.yaml and the parameter reference (docs/parameters.md) from the
# parameter tables (src/app/parameters/core_parameter_table.cpp, src/app/parameters/node_parameter_table.cpp, ...).
# Run it after adding or changing a row; test_parameter_docs fails until the files agree with
# the tables.
set -euo pipefail
# shellcheck source=scripts/workspace.sh
source "$(dirname "${BASH_SOURCE[0]}")/workspace.sh"
ws="${TLC_WS:-$repo/.ws}"
bash "$repo/scripts/build.sh" >/dev/null
(cd "$ws" && catkin_make test_parameter_docs -j"${TLC_JOBS:-$(nproc)}" >&2)
cd "$repo/test"
TLC_UPDATE_PARAMETER_DOCS=1 "$ws/devel/lib/thermal_lidar_calibration/test_parameter_docs" >/dev/null
git -C "$repo" diff --stat -- config/default.yaml docs/parameters.md
