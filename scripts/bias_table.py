#!/usr/bin/env python3
"""Summarises scripts/bias_validation.sh runs: per rig, noise, input and build (label), the
signed difference from the truth per camera axis (mean and min..max over the seeds found), how
many axis checks the 95 % intervals held, and the truth's own Eq. 3 loss beside the result's.
Several labels give the builds row by row, for a before/after table.
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
        "verdict": d.get("verdict", ""),
    }


def cell_text(values, digits):
    fmt = "%+." + str(digits) + "f"
    return (fmt + " (" + fmt + ".." + fmt + ")") % (statistics.mean(values), min(values), max(values))


def load_label(out, label):
    groups = {}
    for path in sorted(glob.glob(os.path.join(out, label, "*.yaml"))):
        input_, rig, noise, _ = os.path.basename(path)[:-5].split(".")
        try:
            groups.setdefault((rig, noise, input_), []).append(load(path))
        except (KeyError, TypeError, yaml.YAMLError):
            print("skipped %s (no reference comparison)" % path)
    for runs in groups.values():
        runs.sort(key=lambda r: r["seed"])
    return groups


def verdicts(runs):
    known = ["good", "usable", "collect_more"]
    counts = [sum(r["verdict"] == v for r in runs) for v in known]
    return "/".join(str(c) for c in counts + [len(runs) - sum(counts)])


def held(runs):
    return sum(sum(r["held"]) for r in runs), sum(len(r["held"]) for r in runs)


def main():
    args = [a for a in sys.argv[1:] if a != "--drives"]
    drives = "--drives" in sys.argv
    out, labels = args[0], args[1:]
    by_label = {label: load_label(out, label) for label in labels}
    cells = sorted(set(key for groups in by_label.values() for key in groups))
    print("Signed difference result - truth, mean (min..max) over the seeds; rotation about the "
          "camera's x, y, z in deg, translation along them in cm; camera x right, y down, z forward.\n")
    print("| rig | noise | input | build | seeds | " + " | ".join(AXES) +
          " | intervals held | loss px | truth's loss px | pairs used/kept | verdicts g/u/c/other |")
    print("|" + "---|" * 15)
    for cell in cells:
        for label in labels:
            runs = by_label[label].get(cell)
            if not runs:
                continue
            cols = [cell_text([r["diff"][k] for r in runs], 3 if k < 3 else 2) for k in range(6)]
            h, n = held(runs)
            print("| %s | %s | %s | %s | %s | %s | %d/%d | %.4f | %.4f | %.0f/%.0f | %s |" % (
                cell[0], cell[1], cell[2], label, " ".join(str(r["seed"]) for r in runs),
                " | ".join(cols), h, n, statistics.mean(r["loss"] for r in runs),
                statistics.mean(r["truth_loss"] for r in runs),
                statistics.mean(r["used"] for r in runs), statistics.mean(r["kept"] for r in runs),
                verdicts(runs)))
    print()
    for label in labels:
        for input_ in ("ideal", "detect"):
            runs = [r for key, rs in by_label[label].items() if key[2] == input_ for r in rs]
            if runs:
                h, n = held(runs)
                print("%s, %s drives: the 95 %% intervals held the truth on %d of %d axis checks (%.0f %%)." % (
                    label, input_, h, n, 100.0 * h / n))
    if drives:
        print("\n| rig | noise | input | build | seed | " + " | ".join(AXES) + " | held | loss | truth's loss |")
        print("|" + "---|" * 14)
        for cell in cells:
            for label in labels:
                for r in by_label[label].get(cell, []):
                    print("| %s | %s | %s | %s | %d | %s | %s | %.4f | %.4f |" % (
                        cell[0], cell[1], cell[2], label, r["seed"],
                        " | ".join("%+.3f" % v if k < 3 else "%+.2f" % v for k, v in enumerate(r["diff"])),
                        "".join("y" if h else "n" for h in r["held"]), r["loss"], r["truth_loss"]))


if __name__ == "__main__":
    main()
