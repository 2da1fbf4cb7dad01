#!/usr/bin/env bash
# Re-measures the accuracy table of the README: over 5 optimizer seeds, the rotation error (deg),
# translation error (cm) and loss of
#   - the paper's method (Algorithm 2, --refine none) on a clean FieldSAFE-like bag, and the same
#     with 16x the generations (a diagnostic: does it converge given time?),
#   - the default (Algorithm 2 + local refinement) on the same bag,
#   - the default on a bag with realistic noise (mask edges +-2 px, 2 cm range noise, false
#     clusters and missed people),
# each beside the loss of the truth on the same pairs. Takes a few minutes on 2 cores.
# Usage: scripts/accuracy.sh [SEEDS...]   (default 1 2 3 4 5)
set -euo pipefail
# shellcheck source=scripts/workspace.sh
source "$(dirname "${BASH_SOURCE[0]}")/workspace.sh"
prepare_workspace
out="${TLC_ACCURACY_OUT:-$repo/out/accuracy}"
mkdir -p "$out"
seeds=("$@")
[ ${#seeds[@]} -gt 0 ] || seeds=(1 2 3 4 5)

"$bin/make_synthetic_bag" --output "$out/clean.bag" --truth "$out/clean.truth.yaml" --seed 1 --noise clean >&2
"$bin/make_synthetic_bag" --output "$out/noisy.bag" --truth "$out/noisy.truth.yaml" --seed 2 --noise realistic >&2

# Diagnostic only: the paper's method unchanged except for 16x Table 1's generations, to show
# whether it converges given time (the paper mode itself always runs Table 1).
echo "max_iterations: 6400" > "$out/long_generations.yaml"

run() {  # name bag truth seed extra-args...
  local name=$1 bag=$2 truth=$3 seed=$4
  shift 4
  "$bin/calibrate_bag" --bag "$bag" --output "$out/$name.seed$seed.yaml" --truth "$truth" \
    --seed "$seed" --quiet "$@" > "$out/$name.seed$seed.log" 2>&1 ||
    { echo "calibrate_bag failed for $name seed $seed (see $out/$name.seed$seed.log)" >&2; return 1; }
}
for seed in "${seeds[@]}"; do
  echo "== seed $seed" >&2
  run paper "$out/clean.bag" "$out/clean.truth.yaml" "$seed" --refine none
  run paper_long "$out/clean.bag" "$out/clean.truth.yaml" "$seed" --refine none \
    --config "$out/long_generations.yaml"
  run default "$out/clean.bag" "$out/clean.truth.yaml" "$seed"
  run noisy_default "$out/noisy.bag" "$out/noisy.truth.yaml" "$seed"
done
/usr/bin/python3 "$repo/scripts/accuracy_table.py" "$out" "${seeds[@]}"
