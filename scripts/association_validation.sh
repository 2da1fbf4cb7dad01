#!/usr/bin/env bash
# Pairing by association against the count rule alone (issue 23), drive by drive: for each rig
# and seed a raw synthetic drive (make_synthetic_bag --raw --noise realistic: full-density points,
# radiometric image, warm confounders, realistic noise) is calibrated twice with --detect:
#   counts       pairing: counts (the paper's rule alone, as before issue 23)
#   association  the default (pairing: association)
# and prints one row per run: pairs by rule, pairs per minute of driving, pairs used, the signed
# error per axis against the truth (rotation about the camera's x, y, z in deg, translation along
# them in cm), the truth's own loss beside the result's, and for the association run how many
# associated persons were matched to the wrong person (bench/score_association.cpp).
# MS2-like drives use config/ms2.yaml. With --ideal, the ideal mask/cluster topics of clean
# drives (no --raw, no --detect) instead. With --association-only, only the association run (for
# its wrong-person count, when the counts run's time is better spent on more seeds). Bags are
# deleted after use.
# Usage: scripts/association_validation.sh [--rig fieldsafe|ms2] [--frames N] [--ideal]
#        [--association-only] [SEEDS...]
set -euo pipefail
# shellcheck source=scripts/workspace.sh
source "$(dirname "${BASH_SOURCE[0]}")/workspace.sh"
prepare_workspace_unless_bin --bench  # TLC_BIN: executables already built
rig=fieldsafe
frames=""
ideal=0
modes=(counts association)
seeds=()
while [ $# -gt 0 ]; do
  case "$1" in
    --rig) rig="$2"; shift 2 ;;
    --frames) frames="$2"; shift 2 ;;
    --ideal) ideal=1; shift ;;
    --association-only) modes=(association); shift ;;
    *) seeds+=("$1"); shift ;;
  esac
done
[ ${#seeds[@]} -gt 0 ] || seeds=(1 2 3 4 5)
[ -n "$frames" ] || { [ "$rig" = ms2 ] && frames=427 || frames=1200; }
out="${TLC_ASSOCIATION_OUT:-$repo/out/association}"
mkdir -p "$out"
base=()
[ "$rig" = ms2 ] && base=(--config "$repo/config/ms2.yaml")
{ [ "$rig" = ms2 ] && cat "$repo/config/ms2.yaml"; printf '\npairing: counts\n'; } > "$out/counts.$rig.yaml"
gen=(--raw --noise realistic)
detect=(--detect)
[ "$ideal" = 1 ] && gen=() && detect=()
tag="$rig$([ "$ideal" = 1 ] && echo .ideal || true)"

row() {  # RESULT TRUTH SEED MODE SCORE_LINE
  PYTHONPATH="$repo/scripts" /usr/bin/python3 - "$@" <<'PY'
import math, sys, yaml
from extrinsic_error import signed_error
res, truth, seed, mode, frames, score = sys.argv[1:7]
r, t = yaml.safe_load(open(res)), yaml.safe_load(open(truth))
a, w, dt = signed_error(r, t)
by = r.get("pairs_by_rule", {"counts": r["pairs_collected"], "association": 0})
minutes = int(frames) / 10.0 / 60.0
print("| %s | %s | %d | %d | %.0f | %d | %s | %s | %.3f | %.2f | %.4f / %.4f | %s |" % (
    seed, mode, by["counts"], by["association"], r["pairs_collected"] / minutes, r["pairs_used"],
    " ".join("%+.3f" % math.degrees(x) for x in w), " ".join("%+.2f" % x for x in dt),
    math.degrees(a), math.sqrt(sum(x * x for x in dt)), r["loss"], r["truth"]["loss"], score))
PY
}

echo "| seed | pairing | counts pairs | association pairs | pairs / min | used | rotation error deg (x y z) | translation error cm (x y z) | rotation deg | translation cm | loss / truth's loss px | wrong person |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
for seed in "${seeds[@]}"; do
  bag="$out/$tag.seed$seed.bag"
  truth="$out/$tag.truth.seed$seed.yaml"
  "$bin/make_synthetic_bag" --rig "$rig" "${gen[@]}" --frames "$frames" --seed "$seed" \
    --output "$bag" --truth "$truth" > "$out/$tag.gen.seed$seed.log" 2>&1
  for mode in "${modes[@]}"; do
    result="$out/$tag.$mode.seed$seed.yaml"
    config=("${base[@]}")
    [ "$mode" = counts ] && config=(--config "$out/counts.$rig.yaml")
    if ! "$bin/calibrate_bag" --bag "$bag" --output "$result" --truth "$truth" --quiet "${detect[@]}" \
        "${config[@]}" > "$out/$tag.$mode.seed$seed.log" 2>&1; then
      echo "| $seed | $mode | failed: $(tail -n 1 "$out/$tag.$mode.seed$seed.log") |"
      continue
    fi
    score="-"
    if [ "$mode" = association ] && [ "$ideal" = 0 ]; then
      "$bin/score_association" --bag "$bag" --result "$result" "${base[@]}" > "$out/$tag.score.seed$seed.log" 2>&1 || true
      score="$(tail -n 1 "$out/$tag.score.seed$seed.log" | sed -n 's/.*persons matched \([0-9]*\): right [0-9]*, wrong \([0-9]*\) (\([0-9.]*\) %).*/\2 of \1 (\3 %)/p')"
    fi
    row "$result" "$truth" "$seed" "$mode" "$frames" "${score:--}"
  done
  rm -f "$bag"
done
