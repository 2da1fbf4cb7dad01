#!/usr/bin/env bash
# The drift watch paired by association against the count rule alone (issue 23), drive by drive:
# each bump drive (240 s, a change at 60 s, make_synthetic_bag --extrinsic-change) is watched
# twice with calibrate_bag --monitor against its starting truth, `pairing: counts` and the default
# (association), and one row per run says the pairs by rule and per minute of driving, the seconds
# from the change to the first ERROR, and the new fit's signed error against the new truth
# (rotation about the camera's x, y, z in deg, translation along them in cm).
# --association-only skips the counts runs (they do not change with the watch's association).
# Usage: scripts/drift_association_validation.sh [--noise clean|realistic] [--change ROT_DEG,TRANS_CM]
#        [--association-only] [SEEDS...]
set -euo pipefail
# shellcheck source=scripts/workspace.sh
source "$(dirname "${BASH_SOURCE[0]}")/workspace.sh"
prepare_workspace_unless_bin  # TLC_BIN: executables already built
noise=clean
change=0.5,0
modes=(counts association)
seeds=()
while [ $# -gt 0 ]; do
  case "$1" in
    --noise) noise="$2"; shift 2 ;;
    --change) change="$2"; shift 2 ;;
    --association-only) modes=(association); shift ;;
    *) seeds+=("$1"); shift ;;
  esac
done
[ ${#seeds[@]} -gt 0 ] || seeds=(1 2 3 4 5)
out="${TLC_DRIFT_OUT:-$repo/out/drift_association}"
mkdir -p "$out"
printf 'pairing: counts\n' > "$out/counts.yaml"

echo "| drive | seed | pairing | pairs (counts + association) | pairs / min | s from change to ERROR | new fit: rotation error deg (x y z) | translation error cm (x y z) |"
echo "|---|---|---|---|---|---|---|---|"
for seed in "${seeds[@]}"; do
  name="$noise.$change.$seed"
  "$bin/make_synthetic_bag" --frames 2400 --seed "$seed" --noise "$noise" --extrinsic-change-at 60 \
    --extrinsic-change "$change" --output "$out/$name.bag" --truth "$out/$name.truth.yaml" > /dev/null 2>&1
  for mode in "${modes[@]}"; do
    config=()
    [ "$mode" = counts ] && config=(--config "$out/counts.yaml")
    "$bin/calibrate_bag" --bag "$out/$name.bag" --monitor --reference "$out/$name.truth.yaml" \
      --output "$out/$name.$mode.yaml" --quiet "${config[@]}" > "$out/$name.$mode.log" 2>&1
    PYTHONPATH="$repo/scripts" /usr/bin/python3 - "$out/$name.$mode.yaml" "$out/$name.truth.yaml" \
      "$noise $change" "$seed" "$mode" <<'PY'
import math, sys, yaml
from extrinsic_error import signed_error
res, truth, drive, seed, mode = sys.argv[1:6]
r, t = yaml.safe_load(open(res)), yaml.safe_load(open(truth))
d, ch = r["drift"], t["extrinsic_change"]
by = d["pairs_by_rule"]
err = d["first_error_stamp"]
to_error = "never" if err is None else "%.1f" % (err - ch["at_stamp"])
if d.get("candidate") is not None or err is not None:
    _, w, dt = signed_error(r, ch["after"])
    fit = (" ".join("%+.3f" % math.degrees(x) for x in w), " ".join("%+.2f" % x for x in dt))
else:
    fit = ("-", "-")
print("| %s | %s | %s | %d + %d | %.1f | %s | %s | %s |" % (
    drive, seed, mode, by["counts"], by["association"], d["pairs"] / 4.0, to_error, fit[0], fit[1]))
PY
  done
  rm -f "$out/$name.bag"
done
