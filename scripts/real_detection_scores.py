#!/usr/bin/env python3
"""Scores detect_people on real labelled samples (issue 23, section 2): thermal images against
PASCAL-VOC person boxes (LLVIP's Annotations/*.xml), KITTI Velodyne scans against label_2.

Thermal, per image: a detected region matches a labelled person when their boxes overlap with
IoU >= 0.5 (one-to-one, best IoU first). A labelled person whose box comes within 1 % of the
image's size of its border is cut by the border and not scored (the synthetic scorer's rule, with
room for a hand-drawn box): a region matching it is ignored, neither right nor wrong; the
"all labels" figures score every labelled person anyway.

LiDAR, per scan: a detected person matches a labelled Pedestrian, Person_sitting or Cyclist when
its centroid lies within 0.6 m (horizontally) of the label's box centre. Only detections in the
camera's view count (centroid projected with calib's Tr_velo_to_cam, R0_rect and P2 inside
image_2's size); labels beyond lidar_max_range_m (30 m) are not scored and detections of them are
ignored.

Usage: real_detection_scores.py --bin DIR [--config PARAMS.yaml] [--llvip DIR] [--kitti DIR]
                                [--work DIR] [--verbose]
(DIR for --llvip holds infrared/*.jpg and Annotations/*.xml; for --kitti velodyne/*.bin,
label_2/*.txt, calib/*.txt and image_2/*.png). Run by scripts/real_detection_scores.sh; never by
the tests.
"""
import argparse
import glob
import math
import os
import struct
import subprocess
import sys
import xml.etree.ElementTree as ET

MIN_IOU = 0.5
BORDER_FRACTION = 0.01
KITTI_MATCH_M = 0.6
KITTI_PEOPLE = ("Pedestrian", "Person_sitting", "Cyclist")
KITTI_MAX_RANGE_M = 30.0


def run(cmd):
    out = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if out.returncode != 0:
        sys.exit("failed: %s\n%s" % (" ".join(cmd), out.stderr))
    return out.stdout, out.stderr


# ---------------------------------------------------------------- thermal images

def voc_people(path):
    root = ET.parse(path).getroot()
    size = root.find("size")
    width, height = int(size.find("width").text), int(size.find("height").text)
    boxes = []
    for obj in root.iter("object"):
        if obj.find("name").text.strip() != "person":
            continue
        b = obj.find("bndbox")
        xmin, ymin, xmax, ymax = (float(b.find(k).text) for k in ("xmin", "ymin", "xmax", "ymax"))
        boxes.append((xmin - 1, ymin - 1, xmax, ymax))  # VOC is 1-based, inclusive
    return width, height, boxes


def iou(a, b):
    ix = max(0.0, min(a[2], b[2]) - max(a[0], b[0]))
    iy = max(0.0, min(a[3], b[3]) - max(a[1], b[1]))
    inter = ix * iy
    union = (a[2] - a[0]) * (a[3] - a[1]) + (b[2] - b[0]) * (b[3] - b[1]) - inter
    return inter / union if union > 0 else 0.0


def match(detections, labels, score):
    """One-to-one matches (detection index -> label index), best score first."""
    pairs = [(score(d, l), i, j) for i, d in enumerate(detections) for j, l in enumerate(labels)]
    pairs = sorted((p for p in pairs if p[0] is not None), reverse=True)
    used_d, used_l, out = set(), set(), {}
    for _, i, j in pairs:
        if i in used_d or j in used_l:
            continue
        used_d.add(i)
        used_l.add(j)
        out[i] = j
    return out


def parse_regions(stdout):
    regions = []
    for line in stdout.splitlines():
        w = line.split()
        if len(w) >= 7 and w[0] == "person" and w[2] == "bbox":
            x, y, bw, bh = (int(v) for v in w[3:7])
            regions.append((x, y, x + bw, y + bh))
    return regions


class Tally:
    def __init__(self):
        self.tp = self.fp = self.fn = self.ignored = 0

    def add(self, tp, fp, fn, ignored=0):
        self.tp += tp
        self.fp += fp
        self.fn += fn
        self.ignored += ignored

    def line(self):
        recall = self.tp / (self.tp + self.fn) if self.tp + self.fn else 1.0
        precision = self.tp / (self.tp + self.fp) if self.tp + self.fp else 1.0
        return "recall %.2f precision %.2f (TP %d, FP %d, FN %d, ignored %d)" % (
            recall, precision, self.tp, self.fp, self.fn, self.ignored)


def score_images(args):
    scored, everyone = Tally(), Tally()
    images = sorted(glob.glob(os.path.join(args.llvip, "infrared", "*.jpg")) +
                    glob.glob(os.path.join(args.llvip, "infrared", "*.png")))
    print("thermal images (%s): IoU >= %.1f; people within %.0f %% of the border not scored" % (
        args.llvip, MIN_IOU, 100 * BORDER_FRACTION))
    for image in images:
        name = os.path.splitext(os.path.basename(image))[0]
        xml = os.path.join(args.llvip, "Annotations", name + ".xml")
        if not os.path.exists(xml):
            continue
        width, height, labels = voc_people(xml)
        cmd = [os.path.join(args.bin, "detect_people"), "--image", image, "--mask-out",
               os.path.join(args.work, name + ".mask.png"), "--explain"]
        if args.config:
            cmd += ["--config", args.config]
        stdout, stderr = run(cmd)
        regions = parse_regions(stdout)
        mx, my = BORDER_FRACTION * width, BORDER_FRACTION * height
        at_border = [l[0] <= mx or l[1] <= my or l[2] >= width - mx or l[3] >= height - my for l in labels]
        matched = match(regions, labels, lambda d, l: iou(d, l) if iou(d, l) >= MIN_IOU else None)
        tp = sum(1 for j in matched.values() if not at_border[j])
        ignored = sum(1 for j in matched.values() if at_border[j])
        fp = len(regions) - len(matched)
        fn = sum(1 for j, b in enumerate(at_border) if not b and j not in matched.values())
        scored.add(tp, fp, fn, ignored)
        everyone.add(tp + ignored, fp, len(labels) - len(matched))
        dropped = sum(1 for l in stderr.splitlines() if "cut_by_border" in l)
        print("  %s: %d labelled (%d at the border), %d regions: %d right, %d false, %d missed, %d ignored;"
              " %d regions dropped at the border" % (name, len(labels), sum(at_border), len(regions), tp, fp, fn,
                                                      ignored, dropped))
        if args.verbose:
            for i, r in enumerate(regions):
                what = "person" if i in matched else "FALSE"
                print("      region %d %s box %d %d %d %d" % (i + 1, what, r[0], r[1], r[2] - r[0], r[3] - r[1]))
            for j, l in enumerate(labels):
                if j not in matched.values():
                    print("      missed%s %d %d %d %d" % (" (border)" if at_border[j] else "", l[0], l[1],
                                                        l[2] - l[0], l[3] - l[1]))
    print("  scored people:  " + scored.line())
    print("  all labels:     " + everyone.line())


# ---------------------------------------------------------------- KITTI scans

def kitti_calib(path):
    values = {}
    for line in open(path):
        if ":" in line:
            key, rest = line.split(":", 1)
            numbers = [float(v) for v in rest.split()]
            if numbers:
                values[key] = numbers
    rows = lambda v, r, c: [v[i * c:(i + 1) * c] for i in range(r)]
    return rows(values["P2"], 3, 4), rows(values["R0_rect"], 3, 3), rows(values["Tr_velo_to_cam"], 3, 4)


def png_size(path):
    with open(path, "rb") as f:
        head = f.read(24)
    return struct.unpack(">II", head[16:24])


def velo_to_rect(calib, p):
    _, r0, tr = calib
    cam = [sum(tr[i][j] * p[j] for j in range(3)) + tr[i][3] for i in range(3)]
    return [sum(r0[i][j] * cam[j] for j in range(3)) for i in range(3)]


def rect_to_velo(calib, q):
    _, r0, tr = calib
    cam = [sum(r0[j][i] * q[j] for j in range(3)) for i in range(3)]  # R0 is a rotation
    d = [cam[i] - tr[i][3] for i in range(3)]
    return [sum(tr[j][i] * d[j] for j in range(3)) for i in range(3)]  # so is Tr's left block


def in_camera_view(calib, size, p):
    q = velo_to_rect(calib, p)
    p2 = calib[0]
    h = [sum(p2[i][j] * q[j] for j in range(3)) + p2[i][3] for i in range(3)]
    if h[2] <= 0.5:
        return False
    u, v = h[0] / h[2], h[1] / h[2]
    return 0 <= u < size[0] and 0 <= v < size[1]


def score_scans(args):
    print("KITTI scans (%s): match within %.1f m; only detections in the camera's view (P2)" % (
        args.kitti, KITTI_MATCH_M))
    total_false = 0
    for scan in sorted(glob.glob(os.path.join(args.kitti, "velodyne", "*.bin"))):
        name = os.path.splitext(os.path.basename(scan))[0]
        calib = kitti_calib(os.path.join(args.kitti, "calib", name + ".txt"))
        size = png_size(os.path.join(args.kitti, "image_2", name + ".png"))
        people = []
        for line in open(os.path.join(args.kitti, "label_2", name + ".txt")):
            w = line.split()
            if w and w[0] in KITTI_PEOPLE:
                h, x, y, z = float(w[8]), float(w[11]), float(w[12]), float(w[13])
                people.append((w[0], rect_to_velo(calib, [x, y - h / 2, z])))
        cmd = [os.path.join(args.bin, "detect_people"), "--cloud", scan, "--clusters-out",
               os.path.join(args.work, name + ".clusters.pcd"), "--explain"]
        if args.config:
            cmd += ["--config", args.config]
        stdout, stderr = run(cmd)
        found = []
        for line in stdout.splitlines():
            w = line.split()
            if len(w) >= 6 and w[0] == "person" and w[2] == "centroid":
                found.append(([float(v) for v in w[3:6]], line))
        in_view = [f for f in found if in_camera_view(calib, size, f[0])]
        dist = lambda d, l: math.hypot(d[0][0] - l[1][0], d[0][1] - l[1][1])
        matched = match(in_view, people, lambda d, l: -dist(d, l) if dist(d, l) <= KITTI_MATCH_M else None)
        far = [math.hypot(l[1][0], l[1][1]) > KITTI_MAX_RANGE_M for l in people]
        right = sum(1 for j in matched.values() if not far[j])
        false = len(in_view) - len(matched)
        missed = sum(1 for j, l in enumerate(people) if not far[j] and j not in matched.values())
        total_false += false
        print("  %s: %d labelled people (%d beyond %.0f m), %d detections (%d in the camera's view): %d right, "
              "%d false, %d missed" % (name, len(people), sum(far), KITTI_MAX_RANGE_M, len(found), len(in_view),
                                        right, false, missed))
        if args.verbose:
            for i, (p, line) in enumerate(in_view):
                print("      %s %s" % ("person" if i in matched else "FALSE ", line))
    print("  false objects in the camera's view: %d" % total_false)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--bin", required=True, help="folder holding detect_people")
    parser.add_argument("--config", help="detector parameters (YAML, flat keys)")
    parser.add_argument("--llvip", help="folder with infrared/ and Annotations/")
    parser.add_argument("--kitti", help="folder with velodyne/, label_2/, calib/, image_2/")
    parser.add_argument("--work", default="/tmp", help="where the masks and clusters are written")
    parser.add_argument("--verbose", action="store_true", help="one line per region / detection")
    args = parser.parse_args()
    os.makedirs(args.work, exist_ok=True)
    if args.llvip:
        score_images(args)
    if args.kitti:
        score_scans(args)


if __name__ == "__main__":
    main()
