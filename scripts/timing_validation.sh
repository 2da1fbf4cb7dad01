#!/usr/bin/env bash
# The camera time offset on synthetic drives (issue 21): for each case, noise and seed, a drive is
# generated and calibrated with the default run (and, where a case says so, with
# time_offset_mode none: today's behaviour), against the drive's truth as --reference, so the
# result file holds the signed difference per camera axis and whether each 95 % interval held it.
# scripts/timing_table.py prints the tables docs/validation/timing.md quotes.
#
# Cases (FieldSAFE-like rig unless named; field speed profile, half the people walking):
#   fs_late60 fs_early40 fs_sync        camera 60 ms late / 40 ms early / synchronised
#   ms2_late60 ms2_early40 ms2_sync     the MS2-like car (config/ms2.yaml)
#   fs_endstamp60 ms2_endstamp60        60 ms late, end-of-scan stamps with per-point times
#   fs_sweep60                          60 ms late, end-of-scan stamps, no per-point times
#   fs_raw60                            60 ms late, raw sensors (--raw, calibrate_bag --detect)
#   fs_raw_sync                         raw sensors, synchronised: what fs_raw60 compares with
#   fs_steady60                         60 ms late, steady straight driving, nobody walking
# Usage: scripts/timing_validation.sh [--cases "A B"] [--noise "clean realistic"]
#          [--modes "default none"] [--frames N] [SEEDS...]
# --frames N drives N frames instead of the generator's 1200 (how the spread falls with the data);
# the runs are named <noise>_<N>f (realistic_2400f), beside the default length's in the same folder.
# --modes keeps only those of a case's runs (a case without a `none` run ignores `none`), so the
# costly runs can go first and the rest follow into the same folder. `fixed` (any case, only when
# asked) is time_offset_mode fixed at the drive's true offset: what is left with the offset known.
# Results in out/timing/<case>.<noise>.seed<N>.<mode>.yaml; an existing result is kept (delete
# the folder to measure again). Bags are deleted after use.
set -euo pipefail
# shellcheck source=scripts/workspace.sh
source "$(dirname "${BASH_SOURCE[0]}")/workspace.sh"
prepare_workspace_unless_bin  # TLC_BIN: executables already built
cases="fs_late60 fs_early40 fs_sync ms2_late60 ms2_early40 ms2_sync fs_endstamp60 ms2_endstamp60 fs_sweep60 fs_raw60 fs_raw_sync fs_steady60"
noises="clean realistic"
wanted="default none"
frames=""
seeds=()
while [ $# -gt 0 ]; do
  case "$1" in
    --cases) cases="$2"; shift 2 ;;
    --noise) noises="$2"; shift 2 ;;
    --modes) wanted="$2"; shift 2 ;;
    --frames) frames="$2"; shift 2 ;;
    *) seeds+=("$1"); shift ;;
  esac
done
[ ${#seeds[@]} -gt 0 ] || seeds=(1 2 3 4 5)
length=()
[ -n "$frames" ] && length=(--frames "$frames")
out="${TLC_TIMING_OUT:-$repo/out/timing}"
mkdir -p "$out"

drive=(--speed-profile field --walking-fraction 0.5)
generator() {  # case -> make_synthetic_bag flags
  case "$1" in
    fs_late60) echo "--rig fieldsafe ${drive[*]} --camera-time-offset 0.06" ;;
    fs_early40) echo "--rig fieldsafe ${drive[*]} --camera-time-offset -0.04" ;;
    fs_sync) echo "--rig fieldsafe ${drive[*]}" ;;
    ms2_late60) echo "--rig ms2 ${drive[*]} --camera-time-offset 0.06" ;;
    ms2_early40) echo "--rig ms2 ${drive[*]} --camera-time-offset -0.04" ;;
    ms2_sync) echo "--rig ms2 ${drive[*]}" ;;
    fs_endstamp60) echo "--rig fieldsafe ${drive[*]} --camera-time-offset 0.06 --lidar-stamp end --lidar-point-time" ;;
    ms2_endstamp60) echo "--rig ms2 ${drive[*]} --camera-time-offset 0.06 --lidar-stamp end --lidar-point-time" ;;
    fs_sweep60) echo "--rig fieldsafe ${drive[*]} --camera-time-offset 0.06 --lidar-stamp end" ;;
    fs_raw60) echo "--rig fieldsafe ${drive[*]} --camera-time-offset 0.06 --raw" ;;
    fs_raw_sync) echo "--rig fieldsafe ${drive[*]} --raw" ;;
    fs_steady60) echo "--rig fieldsafe --speed-profile steady --walking-fraction 0 --camera-time-offset 0.06" ;;
    *) echo "unknown case $1" >&2; exit 2 ;;
  esac
}
modes() {  # case -> the runs on its bag
  case "$1" in
    fs_sync | ms2_sync | fs_late60 | ms2_late60 | fs_raw_sync) echo "default none" ;;
    *) echo "default" ;;
  esac
}

for case_ in $cases; do
  for noise in $noises; do
    for seed in "${seeds[@]}"; do
      name="$case_.$noise${frames:+_${frames}f}.seed$seed"
      todo=()
      for mode in $(modes "$case_") fixed; do
        [[ " $wanted " == *" $mode "* ]] || continue
        [ -s "$out/$name.$mode.yaml" ] || todo+=("$mode")
      done
      [ ${#todo[@]} -gt 0 ] || continue
      bag="$out/$name.bag"
      truth="$out/$name.truth.yaml"
      # shellcheck disable=SC2046
      "$bin/make_synthetic_bag" $(generator "$case_") --noise "$noise" "${length[@]}" --seed "$seed" \
        --output "$bag" --truth "$truth" > "$out/$name.gen.log" 2>&1
      for mode in "${todo[@]}"; do
        config=()
        if [ "$mode" = none ] || [ "$mode" = fixed ]; then  # none: today's behaviour, timing ignored
          { if [[ "$case_" == ms2_* ]]; then cat "$repo/config/ms2.yaml"; printf '\n'; fi
            if [ "$mode" = none ]; then echo "time_offset_mode: none"; else
              # the offset at the scan stamp unless the points carry their own times (as timing_table.py)
              /usr/bin/python3 -c 'import sys, yaml; t = yaml.safe_load(open(sys.argv[1]))
s = t.get("time_offset_s", 0.0) if t.get("lidar_point_time") else t.get("time_offset_at_scan_stamp_s", t.get("time_offset_s", 0.0))
print("time_offset_mode: fixed\ntime_offset_s: %.9g" % s)' "$truth"
            fi; } > "$out/$name.$mode.config.yaml"
          config=(--config "$out/$name.$mode.config.yaml")
        elif [[ "$case_" == ms2_* ]]; then
          config=(--config "$repo/config/ms2.yaml")
        fi
        detect=()
        [[ "$case_" == *_raw* ]] && detect=(--detect)
        SECONDS=0
        if ! "$bin/calibrate_bag" --bag "$bag" --output "$out/$name.$mode.yaml" --truth "$truth" \
            --reference "$truth" --quiet "${config[@]}" "${detect[@]}" > "$out/$name.$mode.log" 2>&1; then
          echo "calibrate_bag failed: $name $mode ($(tail -n 1 "$out/$name.$mode.log"))" >&2
        fi
        echo "$name $mode: ${SECONDS} s" >&2
      done
      rm -f "$bag"
    done
  done
done
/usr/bin/python3 "$repo/scripts/timing_table.py" "$out"
