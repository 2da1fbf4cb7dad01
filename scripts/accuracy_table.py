#!/usr/bin/env python3
"""Summarises scripts/accuracy.sh runs: min / median / max over seeds of the rotation error
(deg), translation error (cm), the result's loss and the truth's loss on the same pairs."""
import math
import statistics
import sys

import yaml


def rotation(path):
    d = yaml.safe_load(open(path))
    r = d["rotation_matrix"]
    return [r[0:3], r[3:6], r[6:9]], d["translation"], d


def errors(result, truth):
    ra, ta, d = rotation(result)
    rb, tb, _ = rotation(truth)
    # angle of Ra^T Rb
    trace = sum(ra[k][i] * rb[k][i] for i in range(3) for k in range(3))
    angle = math.degrees(math.acos(max(-1.0, min(1.0, (trace - 1.0) / 2.0))))
    dist = 100.0 * math.sqrt(sum((a - b) ** 2 for a, b in zip(ta, tb)))
    return angle, dist, d


def spread(values):
    return "%.3f / %.3f / %.3f" % (min(values), statistics.median(values), max(values))


def main():
    out, seeds = sys.argv[1], sys.argv[2:]
    rows = [("paper", "clean bag, Algorithm 2, refine none (the paper)", "clean"),
            ("paper_long", "clean bag, the paper's method with 16x the generations (6400; diagnostic)", "clean"),
            ("default", "clean bag, Algorithm 2 + local refinement (default)", "clean"),
            ("noisy_default", "realistic-noise bag, default", "noisy")]
    print("| run | pairs used/kept | rotation error deg (min/median/max) | translation error cm (min/median/max) | loss px (median) | truth's loss px (median) | seeds with loss below truth's |")
    print("|---|---|---|---|---|---|---|")
    for name, label, bag in rows:
        rot, trans, loss, truth_loss, used, below = [], [], [], [], [], 0
        for seed in seeds:
            a, t, d = errors("%s/%s.seed%s.yaml" % (out, name, seed), "%s/%s.truth.yaml" % (out, bag))
            rot.append(a)
            trans.append(t)
            loss.append(d["loss"])
            # calibrate_bag --truth writes the truth's loss on the same pairs into the result.
            truth_loss.append(d["truth"]["loss"])
            below += d["loss"] <= d["truth"]["loss"]
            used.append("%s/%s" % (d["pairs_used"], d["pairs_collected"]))
        print("| %s | %s | %s | %s | %.3f | %.3f | %d of %d |" % (
            label, used[0], spread(rot), spread(trans), statistics.median(loss),
            statistics.median(truth_loss), below, len(seeds)))


if __name__ == "__main__":
    main()
