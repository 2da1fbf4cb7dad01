#!/usr/bin/env bash
# How often the stated 95 % intervals hold the truth (issue 8): for each drive seed, a synthetic
# bag is calibrated with default settings and --reference its own truth; the result file says,
# per axis, whether the truth's difference lies within the interval. Prints the share of drives
# whose interval held the truth, per axis, and the median half-widths. A second part calibrates
# the first 20, 40 and 60 pairs' worth of one drive to show the intervals shrink with pairs.
# Usage: scripts/uncertainty_validation.sh [--noise clean|realistic] [SEEDS...]  (default 1..10)
set -euo pipefail
# shellcheck source=scripts/workspace.sh
source "$(dirname "${BASH_SOURCE[0]}")/workspace.sh"
prepare_workspace
noise=clean
seeds=()
while [ $# -gt 0 ]; do
  case "$1" in
    --noise) noise="$2"; shift 2 ;;
    *) seeds+=("$1"); shift ;;
  esac
done
[ ${#seeds[@]} -gt 0 ] || seeds=(1 2 3 4 5 6 7 8 9 10)
out="${TLC_ACCURACY_OUT:-$repo/out/uncertainty_validation}/$noise"
mkdir -p "$out"
for seed in "${seeds[@]}"; do
  "$bin/make_synthetic_bag" --noise "$noise" --seed "$seed" --output "$out/drive$seed.bag" \
    --truth "$out/truth$seed.yaml" > "$out/gen$seed.log" 2>&1
  "$bin/calibrate_bag" --bag "$out/drive$seed.bag" --output "$out/result$seed.yaml" \
    --reference "$out/truth$seed.yaml" --quiet > "$out/calibrate$seed.log" 2>&1 ||
    echo "seed $seed: calibrate_bag failed (see $out/calibrate$seed.log)" >&2
  rm -f "$out/drive$seed.bag"
done
# Shrinking with pairs: one drive cut to about 20, 40 and 60 kept pairs (by its length).
for frames in 330 660 1000; do
  "$bin/make_synthetic_bag" --noise "$noise" --seed 1 --frames "$frames" --output "$out/cut$frames.bag" \
    --truth "$out/cut$frames.truth.yaml" > /dev/null 2>&1
  "$bin/calibrate_bag" --bag "$out/cut$frames.bag" --output "$out/cut$frames.yaml" --quiet > /dev/null 2>&1 || true
  rm -f "$out/cut$frames.bag"
done
/usr/bin/python3 - "$out" "$noise" "${seeds[@]}" <<'PY'
import statistics, sys, yaml
out, noise, seeds = sys.argv[1], sys.argv[2], sys.argv[3:]
axes = ["rot x", "rot y", "rot z", "trans x", "trans y", "trans z"]
held = [0] * 6
widths = [[] for _ in range(6)]
n = 0
for seed in seeds:
    try:
        y = yaml.safe_load(open("%s/result%s.yaml" % (out, seed)))
    except OSError:
        continue
    n += 1
    for k, ok in enumerate(y["reference"]["within_uncertainty"]):
        held[k] += bool(ok)
    for k in range(3):
        widths[k].append(y["uncertainty"]["rotation_deg"][k])
        widths[3 + k].append(y["uncertainty"]["translation_cm"][k])
print("%s drives: %d (seeds %s)" % (noise, n, " ".join(seeds)))
print("%-8s %8s %16s" % ("axis", "held", "median +-"))
for k, name in enumerate(axes):
    unit = "deg" if k < 3 else "cm"
    print("%-8s %5d/%-2d %12.3f %s" % (name, held[k], n, statistics.median(widths[k]), unit))
print("intervals against pairs (seed 1):")
for frames in (330, 660, 1000):
    try:
        y = yaml.safe_load(open("%s/cut%d.yaml" % (out, frames)))
    except OSError:
        print("  %4d frames: failed" % frames)
        continue
    u = y["uncertainty"]
    print("  %4d frames, %2d pairs used: rotation +- %s deg, translation +- %s cm" % (
        frames, y["pairs_used"], [round(v, 3) for v in u["rotation_deg"]],
        [round(v, 2) for v in u["translation_cm"]]))
PY
