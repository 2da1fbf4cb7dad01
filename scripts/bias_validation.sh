#!/usr/bin/env bash
# The signed error of a calibration per camera axis over drives (issue 24): for each rig, noise
# preset and drive seed, a synthetic bag is calibrated with `calibrate_bag --seed SEED
# --reference TRUTH` (the MS2-like rig with config/ms2.yaml), and the result file's difference
# from the truth (rotation about camera x, y, z in deg; translation along camera x, y, z in cm;
# result - truth, camera x right, y down, z forward), whether the 95 % intervals held the truth
# and the truth's own Eq. 3 loss are tabulated: mean and min..max over seeds, by rig, noise and
# input (ideal: the bag's ideal mask and cluster topics; detect: make_synthetic_bag --raw and
# calibrate_bag --detect).
#
# Bags are written once to OUT/bags and reused by later runs (ideal ~42 MB each). Raw bags are
# ~1.4 GB: each is deleted after every --bin has calibrated it, unless --keep-raw.
# To compare two builds on the same bags, give each one a label and its executables' folder:
#   --bin before=/path/to/old/devel/lib/thermal_lidar_calibration --bin after=...
# Without --bin the package is built here and labelled "current". Ideal drives take about 20 s
# each, bag included (6 min for seeds 1-5 of both rigs and noises, 2-core VM, 2026-12-01);
# --detect drives much longer (raw bags and the detectors).
# --noise takes the generator's presets (clean, realistic) and, to see which part of the realistic
# preset moves the result, each of its parts alone on a clean drive: range_noise (2 cm),
# mask_edges (+-2 px), misses (3 %), false_clusters (3 %), false_masks (2 %); and the mask edges
# one way only: masks_grown (dilated 0-2 px), masks_shrunk (eroded 0-2 px), masks_shrunk_1px
# (eroded 0-1 px); and the two parts of masks_shrunk: masks_thin_lost (only the parts narrower
# than the erosion lost), masks_outline_eroded (eroded, those parts kept).
# --frames N drives N frames instead of the generator's 1200 (how the spread falls with the data);
# its bags and runs are named <noise>_<N>f (realistic_2400f), a row of their own in the table.
# Usage: scripts/bias_validation.sh [--rigs "fieldsafe ms2"] [--noise "clean realistic"]
#          [--inputs "ideal detect"] [--refine local|none] [--bin LABEL=DIR]... [--keep-raw]
#          [--frames N]
#          [--config LABEL=FILE]...   (FILE's keys for that label's runs, after config/ms2.yaml's)
#          [SEEDS...]                                        (default seeds 1 2 3 4 5)
set -euo pipefail
# shellcheck source=scripts/workspace.sh
source "$(dirname "${BASH_SOURCE[0]}")/workspace.sh"
rigs="fieldsafe ms2"
noises="clean realistic"
inputs="ideal detect"
refine=local
keep_raw=0
frames=""
bins=()
declare -A label_config=()
seeds=()
while [ $# -gt 0 ]; do
  case "$1" in
    --rigs) rigs="$2"; shift 2 ;;
    --noise) noises="$2"; shift 2 ;;
    --inputs) inputs="$2"; shift 2 ;;
    --refine) refine="$2"; shift 2 ;;
    --bin) bins+=("$2"); shift 2 ;;
    --config) label_config["${2%%=*}"]="$(realpath "${2#*=}")"; shift 2 ;;
    --keep-raw) keep_raw=1; shift ;;
    --frames) frames="$2"; shift 2 ;;
    -h|--help) sed -n '2,30p' "${BASH_SOURCE[0]}"; exit 0 ;;
    *) seeds+=("$1"); shift ;;
  esac
done
[ ${#seeds[@]} -gt 0 ] || seeds=(1 2 3 4 5)
length=()
[ -n "$frames" ] && length=(--frames "$frames")
if [ ${#bins[@]} -eq 0 ]; then
  prepare_workspace
  bins=("current=$bin")
fi
out="${TLC_ACCURACY_OUT:-$repo/out/bias_validation}"
mkdir -p "$out/bags"
# The bags come from the first build given: the synthetic rig is the same in all of them.
make_bag="${bins[0]#*=}/make_synthetic_bag"

labels=()
for b in "${bins[@]}"; do labels+=("${b%%=*}"); done

# The generator's options for a --noise name: a preset, or one part of the realistic preset alone.
noise_options() {  # name
  case "$1" in
    range_noise) echo "--noise clean --range-noise-m 0.02" ;;
    mask_edges) echo "--noise clean --mask-edge-px 2" ;;
    masks_grown) echo "--noise clean --mask-edge-px 2 --mask-edge-sign grow" ;;
    masks_shrunk) echo "--noise clean --mask-edge-px 2 --mask-edge-sign shrink" ;;
    masks_shrunk_1px) echo "--noise clean --mask-edge-px 1 --mask-edge-sign shrink" ;;
    masks_thin_lost) echo "--noise clean --mask-edge-px 2 --mask-edge-sign shrink --mask-erosion-part thin" ;;
    masks_outline_eroded) echo "--noise clean --mask-edge-px 2 --mask-edge-sign shrink --mask-erosion-part outline" ;;
    misses) echo "--noise clean --miss-rate 0.03" ;;
    false_clusters) echo "--noise clean --false-cluster-rate 0.03" ;;
    false_masks) echo "--noise clean --false-mask-rate 0.02" ;;
    *) echo "--noise $1" ;;
  esac
}

calibrate() {  # label dir bag truth rig input noise seed
  local label=$1 dir=$2 bag=$3 truth=$4 rig=$5 input=$6 noise=$7 seed=$8
  local name="$input.$rig.$noise.$seed" args=(--refine "$refine")
  mkdir -p "$out/$label"
  # calibrate_bag reads one --config: the rig's keys and the label's go in one file.
  local config="$out/configs/$label.$rig.yaml"
  mkdir -p "$out/configs"
  : > "$config"
  [ "$rig" = ms2 ] && cat "$repo/config/ms2.yaml" >> "$config"
  [ -n "${label_config[$label]:-}" ] && cat "${label_config[$label]}" >> "$config"
  [ -s "$config" ] && args+=(--config "$config")
  [ "$input" = detect ] && args+=(--detect)
  if [ -s "$out/$label/$name.yaml" ]; then return 0; fi  # done by an earlier run
  echo "== $label: $name" >&2
  "$dir/calibrate_bag" --bag "$bag" --output "$out/$label/$name.yaml" --reference "$truth" \
    --seed "$seed" --quiet "${args[@]}" > "$out/$label/$name.log" 2>&1 ||
    echo "calibrate_bag failed for $label $name (see $out/$label/$name.log)" >&2
}

for rig in $rigs; do
  for noise_name in $noises; do
    noise="$noise_name${frames:+_${frames}f}"
    for seed in "${seeds[@]}"; do
      for input in $inputs; do
        kind=ideal
        gen_args=("${length[@]}")
        if [ "$input" = detect ]; then kind=raw; gen_args+=(--raw); fi
        bag="$out/bags/$kind.$rig.$noise.$seed.bag"
        truth="$out/bags/$kind.$rig.$noise.$seed.truth.yaml"
        pending=0
        for label in "${labels[@]}"; do
          [ -s "$out/$label/$input.$rig.$noise.$seed.yaml" ] || pending=1
        done
        [ $pending -eq 1 ] || continue
        if [ ! -s "$bag" ] || [ ! -s "$truth" ]; then
          echo "== making $bag" >&2
          # shellcheck disable=SC2046  # the options are words
          "$make_bag" "${gen_args[@]}" --rig "$rig" $(noise_options "$noise_name") --seed "$seed" \
            --output "$bag" --truth "$truth" > "$out/bags/$kind.$rig.$noise.$seed.log" 2>&1
        fi
        for b in "${bins[@]}"; do
          calibrate "${b%%=*}" "${b#*=}" "$bag" "$truth" "$rig" "$input" "$noise" "$seed"
        done
        if [ "$kind" = raw ] && [ $keep_raw -eq 0 ]; then rm -f "$bag"; fi
      done
    done
  done
done
/usr/bin/python3 "$repo/scripts/bias_table.py" "$out" "${labels[@]}"
