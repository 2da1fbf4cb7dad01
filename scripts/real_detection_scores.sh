#!/usr/bin/env bash
# Scores detect_people on real labelled samples (issue 23): LWIR images with PASCAL-VOC person
# boxes (an LLVIP-like folder: infrared/*.jpg, Annotations/*.xml) and KITTI Velodyne scans
# (velodyne/*.bin, label_2/, calib/, image_2/). scripts/real_detection_scores.py says how each is
# scored. Not run by the tests; the samples are not part of the package (licences).
# Usage: scripts/real_detection_scores.sh [--llvip DIR] [--kitti DIR] [--config PARAMS.yaml] [--verbose]
set -euo pipefail
# shellcheck source=scripts/workspace.sh
source "$(dirname "${BASH_SOURCE[0]}")/workspace.sh"
prepare_workspace
out="${TLC_ACCURACY_OUT:-$repo/out/real_detection_scores}"
mkdir -p "$out"
/usr/bin/python3 "$repo/scripts/real_detection_scores.py" --bin "$bin" --work "$out" "$@"
