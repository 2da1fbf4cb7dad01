#!/usr/bin/env python3
"""Summarises scripts/accuracy.sh runs: min / median / max over seeds of the rotation error
(deg), translation error (cm), the result's loss and the truth's loss on the same pairs."""
import math
import re
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
            ("default", "clean bag, Algorithm 2 + local refinement (default)", "clean"),
            ("noisy_default", "realistic-noise bag, default", "noisy")]
    print("| run | pairs used/kept | rotation error deg (min/median/max) | translation error cm (min/median/max) | loss px (median) | truth loss px |")
    print("|---|---|---|---|---|---|")
    for name, label, bag in rows:
        rot, trans, loss, truth_loss, used = [], [], [], [], []
        for seed in seeds:
            a, t, d = errors("%s/%s.seed%s.yaml" % (out, name, seed), "%s/%s.truth.yaml" % (out, bag))
            rot.append(a)
            trans.append(t)
            loss.append(d["loss"])
            log = open("%s/%s.seed%s.log" % (out, name, seed)).read()
            m = re.search(r"loss of truth ([0-9.eE+-]+) px", log)
            if m:
                truth_loss.append(float(m.group(1)))
            used.append("%s/%s" % (d["pairs_used"], d["pairs_collected"]))
        tl = "%.3f" % statistics.median(truth_loss) if truth_loss else "see log"
        print("| %s | %s | %s | %s | %.3f | %s |" % (label, used[0], spread(rot), spread(trans),
                                                    statistics.median(loss), tl))


if __name__ == "__main__":
    main()
