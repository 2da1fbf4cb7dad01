#!/usr/bin/python3
"""Where a synthetic drive's LiDAR person points fall against its person masks at the TRUE
extrinsic, by the people's depth: the share of points outside their masks and their mean
distance beyond the outline (`refine_outline_px` 0.5: half a pixel past the covered pixel
centres), split by where the point lies against its mask (above it, below it, left of it, right
of it). A clean drive's truth should fit its own masks the same way near and far, up and down,
left and right; where it does not, the mask loss prefers another pose (docs/validation/accuracy.md,
"The truth's own residuals").

Usage: truth_residuals.py [--by-height] BAG TRUTH.yaml [MAX_FRAMES]
  --by-height  rows by each point's height above the ground (the truth's lidar_height_m over a
               flat ground), 0.2 m apart up to 1.8 m and one row above, instead of by each
               person's depth
  BAG    a make_synthetic_bag bag with masks and clusters (/thermal/human_mask,
         /lidar/human_clusters); the truth's plumb_bob lens model is applied
  TRUTH  its --truth file
Reads the bag with rosbag and sensor_msgs.point_cloud2 (python3-rosbag, python3-sensor-msgs); run
with Debian's /usr/bin/python3."""
import collections
import math
import sys

try:
    import rosbag
    import yaml
    from sensor_msgs import point_cloud2
except ImportError as missing:
    sys.exit("truth_residuals: %s: run it with Debian's /usr/bin/python3 after bash scripts/install_deps.sh"
             % missing)

OUTLINE_PX = 0.5
DEPTH_BINS_M = [0, 8, 12, 16, 20, 25, 35, 60]
HEIGHT_BIN_M = 0.2
HEIGHT_ROWS = 10  # the last row holds every point from 1.8 m up
SEARCH_PX = 4  # a point further than this from every mask pixel counts as this far


def cloud_points(msg):
    """(x, y, z, label) of every point of a PointCloud2 with x, y, z and a label field."""
    names = {f.name for f in msg.fields}
    if not {"x", "y", "z", "label"} <= names:
        sys.exit("truth_residuals: the clusters have no x, y, z and label fields")
    return list(point_cloud2.read_points(msg, field_names=("x", "y", "z", "label")))


def nearest_mask_pixel(mask, width, height, u, v):
    """(distance from the pixel holding (u, v) to the nearest covered pixel, in whole pixels as
    the loss's nearest-pixel distance map reads it; its row offset; its column offset), searching
    SEARCH_PX around the point."""
    cu, cv = int(round(u)), int(round(v))
    if mask[cv * width + cu]:
        return (0.0, 0.0, 0.0)
    best = (float(SEARCH_PX), 0.0, 0.0)
    for r in range(max(0, cv - SEARCH_PX), min(height, cv + SEARCH_PX + 1)):
        row = r * width
        for c in range(max(0, cu - SEARCH_PX), min(width, cu + SEARCH_PX + 1)):
            if mask[row + c]:
                d = math.hypot(c - cu, r - cv)
                if d < best[0]:
                    best = (d, r - cv, c - cu)
    return best


def main():
    args = sys.argv[1:]
    by_height = bool(args) and args[0] == "--by-height"
    if by_height:
        args = args[1:]
    if len(args) not in (2, 3):
        sys.exit(__doc__)
    bag_path, truth_path = args[0], args[1]
    with open(truth_path) as f:
        truth = yaml.safe_load(f)
    if not isinstance(truth, dict) or "rotation_matrix" not in truth:
        sys.exit("truth_residuals: %s is not a make_synthetic_bag truth file (no rotation_matrix)" % truth_path)
    if truth.get("distortion_model", "plumb_bob") != "plumb_bob":
        sys.exit("truth_residuals: only the plumb_bob lens model is read")
    k1, k2, p1, p2, k3 = (list(truth.get("distortion_coefficients", [])) + [0.0] * 5)[:5]
    max_frames = int(args[2]) if len(args) == 3 else 10 ** 9
    lidar_height = truth.get("lidar_height_m", 0.0)
    R = truth["rotation_matrix"]
    t = truth["translation"]
    fx, _, cx, _, fy, cy = truth["camera_matrix"][:6]
    masks, clouds = {}, {}
    with rosbag.Bag(bag_path) as bag:
        for topic, msg, _ in bag.read_messages(topics=["/thermal/human_mask", "/lidar/human_clusters"]):
            stamp = msg.header.stamp.to_nsec()
            if topic == "/thermal/human_mask":
                if msg.step != msg.width:
                    sys.exit("truth_residuals: expected a mono8 mask without row padding")
                masks[stamp] = (bytes(msg.data), msg.width, msg.height)
            else:
                clouds[stamp] = cloud_points(msg)
    stamps = sorted(set(masks) & set(clouds))[:max_frames]
    if not stamps:
        sys.exit("truth_residuals: no frame has both a mask and clusters")
    acc = collections.defaultdict(lambda: collections.Counter())
    for stamp in stamps:
        mask, width, height = masks[stamp]
        people = collections.defaultdict(list)
        for x, y, z, label in clouds[stamp]:
            pc = [R[3 * i] * x + R[3 * i + 1] * y + R[3 * i + 2] * z + t[i] for i in range(3)]
            if pc[2] > 0.5:
                # plumb_bob, as OpenCV's projectPoints
                a, b = pc[0] / pc[2], pc[1] / pc[2]
                r2 = a * a + b * b
                radial = 1 + k1 * r2 + k2 * r2 * r2 + k3 * r2 * r2 * r2
                ad = a * radial + 2 * p1 * a * b + p2 * (r2 + 2 * a * a)
                bd = b * radial + p1 * (r2 + 2 * b * b) + 2 * p2 * a * b
                people[label].append((fx * ad + cx, fy * bd + cy, pc[2], z + lidar_height))
        for points in people.values():
            points = [p for p in points if 0 <= round(p[0]) < width and 0 <= round(p[1]) < height]
            if len(points) < 3:
                continue
            depth = sorted(p[2] for p in points)[len(points) // 2]
            b = max(0, min(len(DEPTH_BINS_M) - 2, sum(1 for edge in DEPTH_BINS_M if edge <= depth) - 1))
            for u, v, _, above_ground in points:
                a = acc[max(0, min(HEIGHT_ROWS - 1, int(above_ground / HEIGHT_BIN_M)))] if by_height else acc[b]
                a["points"] += 1
                d, dv, du = nearest_mask_pixel(mask, width, height, u, v)
                beyond = max(0.0, d - OUTLINE_PX)
                if beyond <= 0.0:
                    continue
                a["outside"] += 1
                a["loss"] += beyond
                if abs(dv) >= abs(du):
                    a["above" if dv > 0 else "below"] += beyond  # dv > 0: the mask lies below the point
                else:
                    a["left" if du > 0 else "right"] += beyond  # du > 0: the mask lies right of the point
    print("%d frames of %s; loss per point in px beyond the outline (%.1f px past the pixel centres)"
          % (len(stamps), bag_path, OUTLINE_PX))
    print("| %s | points | outside %% | loss/point | above | below | left | right |"
          % ("height above the ground m" if by_height else "person's depth m"))
    print("|---|---|---|---|---|---|---|---|")
    for b in sorted(acc):
        a = acc[b]
        n = a["points"]
        if n == 0:
            continue
        if not by_height:
            rows = "%d-%d" % (DEPTH_BINS_M[b], DEPTH_BINS_M[b + 1])
        elif b == HEIGHT_ROWS - 1:
            rows = "%.1f+" % (b * HEIGHT_BIN_M)
        else:
            rows = "%.1f-%.1f" % (b * HEIGHT_BIN_M, (b + 1) * HEIGHT_BIN_M)
        print("| %s | %d | %.1f | %.4f | %.4f | %.4f | %.4f | %.4f |" % (
            rows, n, 100.0 * a["outside"] / n, a["loss"] / n, a["above"] / n, a["below"] / n, a["left"] / n,
            a["right"] / n))


if __name__ == "__main__":
    try:
        main()
    except (OSError, yaml.YAMLError, rosbag.ROSBagException, KeyError, ValueError) as e:
        first_line = (str(e).splitlines() or [""])[0]
        sys.exit("truth_residuals: %s: %s (give a make_synthetic_bag bag and its --truth file)"
                 % (type(e).__name__, first_line))
