#!/usr/bin/env python3
"""Summarises scripts/timing_validation.sh: per case, noise and mode, the signed difference from
the truth per camera axis (mean and min..max over seeds), the time offset against the truth's,
how often the 95 % intervals held, the verdicts, and the truth's own loss beside the result's.
Usage: timing_table.py OUT [--drives]   (--drives also lists every drive)"""
import collections
import glob
import os
import statistics
import sys

import yaml

AXES = ["rot x", "rot y", "rot z", "trans x", "trans y", "trans z"]


def load(path):
    base = os.path.basename(path)[:-5]
    case, noise, seed, mode = base.split(".")
    with open(path) as f:
        d = yaml.safe_load(f)
    with open(os.path.join(os.path.dirname(path), "%s.%s.%s.truth.yaml" % (case, noise, seed))) as f:
        truth = yaml.safe_load(f)
    point_times = bool(truth.get("lidar_point_time", False))
    true_offset = truth.get("time_offset_s", 0.0) if point_times else \
        truth.get("time_offset_at_scan_stamp_s", truth.get("time_offset_s", 0.0))
    ref = d["reference"]
    u = d.get("uncertainty", {})
    return {
        "case": case, "noise": noise, "seed": int(seed[4:]), "mode": mode,
        "diff": list(ref["rotation_difference_axes_deg"]) + list(ref["translation_difference_cm"]),
        "rot_err": d["truth"]["rotation_error_deg"], "trans_err": 100 * d["truth"]["translation_error_m"],
        "held": [bool(v) for v in ref.get("within_uncertainty") or []],
        "loss": d["loss"], "truth_loss": ref["loss"],
        "offset_ms": 1000 * d.get("time_offset_s", 0.0), "true_ms": 1000 * true_offset,
        "offset_mode": d.get("time_offset_mode", "none"), "half_ms": u.get("time_offset_ms"),
        "resolution_ms": (d.get("timing") or {}).get("resolution_ms"),
        "verdict": d.get("verdict", "?"), "reason": (d.get("verdict_reasons") or [""])[0],
        "used": d["pairs_used"], "kept": d["pairs_collected"], "seconds": d.get("run_time_s", 0.0),
    }


def cell(values, digits):
    fmt = "%+." + str(digits) + "f"
    return (fmt + " (" + fmt + ".." + fmt + ")") % (statistics.mean(values), min(values), max(values))


def main():
    out = sys.argv[1]
    drives = "--drives" in sys.argv
    runs = []
    for path in sorted(glob.glob(os.path.join(out, "*.*.seed*.*.yaml"))):
        if path.endswith(".truth.yaml") or path.endswith(".config.yaml"):
            continue
        try:
            runs.append(load(path))
        except (KeyError, TypeError, ValueError, FileNotFoundError, yaml.YAMLError) as e:
            print("skipped %s (%s)" % (path, e))
    groups = collections.OrderedDict()
    for r in sorted(runs, key=lambda r: (r["case"], r["noise"], r["mode"], r["seed"])):
        groups.setdefault((r["case"], r["noise"], r["mode"]), []).append(r)

    print("Signed difference result - truth, mean (min..max) over seeds; rotation about the camera's x, y, z "
          "in deg, translation along them in cm.\n")
    print("| case | noise | mode | seeds | " + " | ".join(AXES) + " | worst deg / cm | intervals held | "
          "loss px | truth's loss px |")
    print("|" + "---|" * 14)
    for (case, noise, mode), rs in groups.items():
        cols = [cell([r["diff"][k] for r in rs], 3 if k < 3 else 2) for k in range(6)]
        held = sum(sum(r["held"]) for r in rs)
        checks = sum(len(r["held"]) for r in rs)
        print("| %s | %s | %s | %d | %s | %.3f / %.2f | %d/%d | %.4f | %.4f |" % (
            case, noise, mode, len(rs), " | ".join(cols), max(r["rot_err"] for r in rs),
            max(r["trans_err"] for r in rs), held, checks, statistics.mean(r["loss"] for r in rs),
            statistics.mean(r["truth_loss"] for r in rs)))

    print("\nTime offset: truth, estimate mean (min..max), worst |error|, estimates inside their own "
          "95 % interval, the drive's resolution (1 sigma), verdicts, optimizer time.\n")
    print("| case | noise | mode | truth ms | estimate ms | worst error ms | inside interval | resolution ms | "
          "verdicts | optimizer s |")
    print("|" + "---|" * 10)
    for (case, noise, mode), rs in groups.items():
        errors = [abs(r["offset_ms"] - r["true_ms"]) for r in rs]
        inside = [r for r in rs if r["half_ms"] is not None and abs(r["offset_ms"] - r["true_ms"]) <= r["half_ms"]]
        timed = [r for r in rs if r["half_ms"] is not None]
        res = [r["resolution_ms"] for r in rs if isinstance(r["resolution_ms"], (int, float))]
        verdicts = collections.Counter(r["verdict"] for r in rs)
        print("| %s | %s | %s | %+.0f | %s | %.1f | %s | %s | %s | %.2f |" % (
            case, noise, mode, rs[0]["true_ms"], cell([r["offset_ms"] for r in rs], 1), max(errors),
            "%d/%d" % (len(inside), len(timed)) if timed else "-",
            ("%.1f..%.1f" % (min(res), max(res))) if res else "-",
            ", ".join("%s %d" % kv for kv in sorted(verdicts.items())),
            statistics.mean(r["seconds"] for r in rs)))
    if drives:
        print("\n| case | noise | mode | seed | applied | offset ms | +- ms | rot deg | trans cm | pairs used/kept | "
              "verdict | first reason |")
        print("|" + "---|" * 12)
        for rs in groups.values():
            for r in rs:
                print("| %s | %s | %s | %d | %s | %+.1f | %s | %.3f | %.2f | %d/%d | %s | %s |" % (
                    r["case"], r["noise"], r["mode"], r["seed"], r["offset_mode"], r["offset_ms"],
                    "%.1f" % r["half_ms"] if r["half_ms"] is not None else "-", r["rot_err"], r["trans_err"],
                    r["used"], r["kept"], r["verdict"], r["reason"][:90]))


if __name__ == "__main__":
    main()
