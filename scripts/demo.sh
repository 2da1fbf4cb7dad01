#!/usr/bin/env bash
# End to end on a fresh Debian 12 machine: installs what it needs, builds, generates a synthetic
# FieldSAFE-like bag (thermal camera + HDL-32E among people), calibrates it with calibrate_bag
# (Algorithm 2 + local refinement), and prints the result beside the truth.
# Output in out/demo/ (bag, truth, result YAML). Options are passed to calibrate_bag, e.g.
#   scripts/demo.sh --refine none      # the paper's method exactly
set -euo pipefail
# shellcheck source=scripts/workspace.sh
source "$(dirname "${BASH_SOURCE[0]}")/workspace.sh"
prepare_workspace
out="${TLC_DEMO_OUT:-$repo/out/demo}"
mkdir -p "$out"
echo "== generating a synthetic FieldSAFE-like bag" >&2
"$bin/make_synthetic_bag" --output "$out/demo.bag" --truth "$out/truth.yaml" --seed 1
echo "== calibrating it" >&2
"$bin/calibrate_bag" --bag "$out/demo.bag" --output "$out/result.yaml" --truth "$out/truth.yaml" "$@"
echo "== result file: $out/result.yaml" >&2
