#!/usr/bin/env python3
"""Summarises scripts/bias_validation.sh runs: per label, rig, noise and input, the signed
difference from the truth per camera axis (mean and min..max over the seeds found), how many
axis checks the 95 % intervals held, and the truth's own Eq. 3 loss beside the result's.
Usage: bias_table.py OUT LABEL... [--drives]   (--drives also lists every drive)"""
import glob
import os
import statistics
import sys

import yaml

AXES = ["rot x", "rot y", "rot z", "trans x", "trans y", "trans z"]


def load(path):
    with open(path) as f:
        d = yaml.safe_load(f)
    ref = d["reference"]
    return {
        "seed": int(os.path.basename(path).split(".")[3]),
        "diff": list(ref["rotation_difference_axes_deg"]) + list(ref["translation_difference_cm"]),
        "held": [bool(v) for v in ref.get("within_uncertainty") or []],
        "loss": d["loss"],
        "truth_loss": ref["loss"],
        "used": d["pairs_used"],
        "kept": d["pairs_collected"],
        "seconds": d.get("run_time_s", 0.0),
    }


def cell(values, digits):
    fmt = "%+." + str(digits) + "f"
    return (fmt + " (" + fmt + ".." + fmt + ")") % (statistics.mean(values), min(values), max(values))


def main():
    args = [a for a in sys.argv[1:] if a != "--drives"]
    drives = "--drives" in sys.argv
    out, labels = args[0], args[1:]
    for label in labels:
        groups = {}
        for path in sorted(glob.glob(os.path.join(out, label, "*.yaml"))):
            input_, rig, noise, _ = os.path.basename(path)[:-5].split(".")
            try:
                groups.setdefault((rig, noise, input_), []).append(load(path))
            except (KeyError, TypeError, yaml.YAMLError):
                print("skipped %s (no reference comparison)" % path)
        print("\n### %s\n" % label)
        print("Signed difference result - truth, mean (min..max) over seeds; rotation about the "
              "camera's x, y, z in deg, translation along them in cm.\n")
        print("| rig | noise | input | seeds | " + " | ".join(AXES) +
              " | intervals held | loss px | truth's loss px | pairs used/kept | optimizer s |")
        print("|" + "---|" * 14)
        for (rig, noise, input_), runs in sorted(groups.items()):
            runs.sort(key=lambda r: r["seed"])
            cols = [cell([r["diff"][k] for r in runs], 3 if k < 3 else 2) for k in range(6)]
            held = sum(sum(r["held"]) for r in runs)
            checks = sum(len(r["held"]) for r in runs)
            print("| %s | %s | %s | %s | %s | %d/%d | %.4f | %.4f | %.0f/%.0f | %.0f |" % (
                rig, noise, input_, " ".join(str(r["seed"]) for r in runs), " | ".join(cols),
                held, checks, statistics.mean(r["loss"] for r in runs),
                statistics.mean(r["truth_loss"] for r in runs),
                statistics.mean(r["used"] for r in runs), statistics.mean(r["kept"] for r in runs),
                statistics.mean(r["seconds"] for r in runs)))
        if drives:
            print("\n| rig | noise | input | seed | " + " | ".join(AXES) + " | held | loss | truth's loss |")
            print("|" + "---|" * 13)
            for (rig, noise, input_), runs in sorted(groups.items()):
                for r in runs:
                    print("| %s | %s | %s | %d | %s | %s | %.4f | %.4f |" % (
                        rig, noise, input_, r["seed"],
                        " | ".join("%+.3f" % v if k < 3 else "%+.2f" % v for k, v in enumerate(r["diff"])),
                        "".join("y" if h else "n" for h in r["held"]), r["loss"], r["truth_loss"]))
        ideal = [r for (rig, noise, input_), runs in groups.items() if input_ == "ideal" for r in runs]
        if ideal:
            held = sum(sum(r["held"]) for r in ideal)
            checks = sum(len(r["held"]) for r in ideal)
            print("\nIdeal-topic drives: intervals held the truth on %d of %d axis checks (%.0f %%)." % (
                held, checks, 100.0 * held / max(checks, 1)))


if __name__ == "__main__":
    main()
