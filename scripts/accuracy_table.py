#!/usr/bin/env python3
"""Summarises scripts/accuracy.sh runs: min / median / max over seeds of the rotation error
(deg), translation error (cm), the result's loss and the truth's loss on the same pairs."""
import statistics
import sys

import yaml


def spread(values):
    return "%.3f / %.3f / %.3f" % (min(values), statistics.median(values), max(values))


def main():
    out, seeds = sys.argv[1], sys.argv[2:]
    rows = [("paper", "clean bag, Algorithm 2, refine none (the paper)"),
            ("paper_long", "clean bag, the paper's method with 16x the generations (6400; diagnostic)"),
            ("default", "clean bag, Algorithm 2 + local refinement (default)"),
            ("noisy_default", "realistic-noise bag, default")]
    print("| run | pairs used/kept | rotation error deg (min/median/max) | translation error cm (min/median/max) | loss px (median) | truth's loss px (median) | seeds ending at or below the truth's loss |")
    print("|---|---|---|---|---|---|---|")
    for name, label in rows:
        rot, trans, loss, truth_loss, used, below = [], [], [], [], [], 0
        for seed in seeds:
            with open("%s/%s.seed%s.yaml" % (out, name, seed)) as f:
                d = yaml.safe_load(f)
            # calibrate_bag --truth writes the errors against the truth and the truth's loss on
            # the same pairs into the result.
            truth = d["truth"]
            rot.append(truth["rotation_error_deg"])
            trans.append(100.0 * truth["translation_error_m"])
            loss.append(d["loss"])
            truth_loss.append(truth["loss"])
            below += d["loss"] <= truth["loss"]
            used.append("%s/%s" % (d["pairs_used"], d["pairs_collected"]))
        print("| %s | %s | %s | %s | %.3f | %.3f | %d of %d |" % (
            label, used[0], spread(rot), spread(trans), statistics.median(loss),
            statistics.median(truth_loss), below, len(seeds)))


if __name__ == "__main__":
    main()
