#!/usr/bin/env python3
"""Kill and resume: calibration_node is killed (SIGKILL) half way through a generated bag,
restarted with ~resume:=true, and must finish with the pairs it had plus new ones.

The bag is played by paced_bag_player (as fast as the node takes it): the first run pauses once
the node has kept half the pairs it needs and has taken everything sent, so the kill comes at a
known count on any machine.

Runs under rostest (node_resume.test) with params ~work_dir and ~config_files.
"""
import math
import os
import shutil
import signal
import subprocess
import threading
import time
import unittest

import rosbag
import rospy
import rostest
import tf2_ros
import yaml
from geometry_msgs.msg import TransformStamped
from std_msgs.msg import UInt32
from std_srvs.srv import Trigger
from thermal_lidar_calibration.msg import CalibrationStatus

from package_executables import executable

NODE = "/calibration_node"
PKG = "thermal_lidar_calibration"

# The deadline of every wait: it only stops a hung test (a slow machine gets there later).
HANG_GUARD_S = 120


class Statuses:
    def __init__(self):
        self.lock = threading.Lock()
        self.last = None
        self.first_after_start = None

    def reset(self):
        with self.lock:
            self.last = None
            self.first_after_start = None

    def callback(self, msg):
        with self.lock:
            self.last = msg
            if self.first_after_start is None:
                self.first_after_start = msg


# Real sensor stamps carry arbitrary nanoseconds; the generator's come from doubles and survive
# toSec() -> ros::Time(double). Shifting them by a few ns (not a multiple of the ~238 ns spacing of
# doubles near 1.6e9 s) makes them not round-trip, so ~resume must de-duplicate on exact stamps.
STAMP_SHIFT_NS = 77
SHIFTED_TOPICS = ("/thermal/image_raw", "/thermal/human_mask", "/lidar/human_clusters",
                  "/thermal/camera_info")


def cpp_time_round_trips(stamp):
    """ros::Time(stamp.toSec()) == stamp, with roscpp's arithmetic (floor sec, round nsec)."""
    t = float(stamp.secs) + 1e-9 * float(stamp.nsecs)
    sec = math.floor(t)
    nsec = int(math.floor((t - sec) * 1e9 + 0.5))
    return (sec + nsec // 1000000000, nsec % 1000000000) == (stamp.secs, stamp.nsecs)


def shift_stamps(src, dst):
    """Copies bag src to dst with the frame topics' header stamps (and times) shifted."""
    shift = rospy.Duration(0, STAMP_SHIFT_NS)
    images = round_trips = 0
    with rosbag.Bag(src) as inp, rosbag.Bag(dst, "w") as out:
        # Keep each connection's header (a latched topic stays latched in the copy).
        for topic, msg, t, header in inp.read_messages(return_connection_header=True):
            if topic in SHIFTED_TOPICS:
                msg.header.stamp = msg.header.stamp + shift
                t = t + shift
                if topic == SHIFTED_TOPICS[0]:
                    images += 1
                    round_trips += cpp_time_round_trips(msg.header.stamp)
            out.write(topic, msg, t, connection_header=header)
    return images, round_trips


def stored_frames(path, with_skipped=False):
    """(pairs, association candidates, newest stamp) the dataset bag's markers list; with_skipped:
    (pairs, candidates, skipped frames held for the final round, newest stamp)."""
    pairs = candidates = skipped = 0
    newest = 0.0
    with rosbag.Bag(path) as bag:
        for topic, msg, t in bag.read_messages(topics=["/thermal_lidar_calibration/dataset_pair",
                                                        "/thermal_lidar_calibration/dataset_candidate",
                                                        "/thermal_lidar_calibration/dataset_skipped"]):
            if topic.endswith("candidate"):
                assert msg.data.startswith("association candidate held by calibration_node; frame "), msg.data
                candidates += 1
            elif topic.endswith("skipped"):
                assert msg.data.startswith("skipped frame held by calibration_node for the final round; frame "), \
                    msg.data
                skipped += 1
                continue  # a skipped frame lies between pairs: not the newest kept one
            else:
                pairs += 1
            newest = max(newest, t.to_sec())
    if with_skipped:
        return pairs, candidates, skipped, newest
    return pairs, candidates, newest


def wait_for(predicate, timeout_s=HANG_GUARD_S):
    end = time.time() + timeout_s
    while time.time() < end and not rospy.is_shutdown():
        if predicate():
            return True
        time.sleep(0.05)
    return predicate()


class KillAndResume(unittest.TestCase):
    def setUp(self):
        self.work = rospy.get_param("~work_dir")
        shutil.rmtree(self.work, ignore_errors=True)
        os.makedirs(self.work)
        generated = os.path.join(self.work, "generated.bag")
        with open(os.path.join(self.work, "generator.log"), "w") as log:
            subprocess.run([executable("make_synthetic_bag"), "--output", generated, "--truth",
                            os.path.join(self.work, "truth.yaml"), "--frames", "300", "--seed", "11",
                            "--noise", "realistic"],
                           check=True, stdout=log, stderr=subprocess.STDOUT)
        self.bag = os.path.join(self.work, "synthetic.bag")
        images, round_trips = shift_stamps(generated, self.bag)
        self.assertGreater(images, 0)
        self.assertEqual(round_trips, 0, "shifted image stamps still survive toSec()")
        for path in rospy.get_param("~config_files").split():
            with open(path) as f:
                for key, value in (yaml.safe_load(f) or {}).items():
                    rospy.set_param(NODE + "/" + key, value)
        self.result_file = os.path.join(self.work, "result.yaml")
        self.dataset_bag = os.path.join(self.work, "dataset.bag")
        rospy.set_param(NODE + "/output_file", self.result_file)
        rospy.set_param(NODE + "/dataset_bag", self.dataset_bag)
        rospy.set_param(NODE + "/resume", False)
        self.statuses = Statuses()
        self.sub = rospy.Subscriber(NODE + "/status", CalibrationStatus, self.statuses.callback,
                                    queue_size=100)
        self.paused = []
        self.paused_sub = rospy.Subscriber("/player/paused", UInt32, lambda m: self.paused.append(m.data))
        self.procs = []

    def tearDown(self):
        for p in self.procs:
            if p.poll() is None:
                p.send_signal(signal.SIGINT)
                try:
                    p.wait(timeout=5)
                except subprocess.TimeoutExpired:
                    p.kill()

    def start(self, args):
        log = open(os.path.join(self.work, "proc%d.log" % len(self.procs)), "w")
        p = subprocess.Popen(args, stdout=log, stderr=subprocess.STDOUT)
        self.procs.append(p)
        return p

    def start_node(self):
        self.statuses.reset()
        node = self.start([executable("calibration_node"), "__name:=calibration_node"])
        self.assertTrue(wait_for(lambda: self.statuses.last is not None), "no ~status")
        return node

    def play(self, *options):
        return self.start([executable("paced_bag_player"), self.bag, "__name:=player"] + list(options))

    def test_kill_half_way_then_resume(self):
        required = rospy.get_param(NODE + "/pairs_required")
        node = self.start_node()
        half = required // 2
        play = self.play("--pause-after-pairs", str(half))
        self.assertTrue(wait_for(lambda: self.paused), "the player never paused: %s" % self.statuses.last)
        kept_before = self.paused[0]  # every message sent was taken: the node is idle
        os.kill(node.pid, signal.SIGKILL)  # no chance to clean up
        node.wait()
        play.send_signal(signal.SIGINT)
        play.wait()
        self.assertGreaterEqual(kept_before, half)
        self.assertLess(kept_before, required)
        self.assertTrue(os.path.exists(self.dataset_bag))
        self.assertFalse(os.path.exists(self.result_file))
        # Pairing by association (the default): the frames held as candidates are in the bag too.
        stored_pairs, stored_candidates, killed_at = stored_frames(self.dataset_bag)
        self.assertEqual(stored_pairs, kept_before)
        self.assertGreater(stored_candidates, 0, "no association candidate in the dataset bag")

        rospy.set_param(NODE + "/resume", True)
        self.start_node()
        resumed = self.statuses.first_after_start.pairs_resumed
        self.assertEqual(resumed, kept_before, "pairs lost by the kill (or more than were kept)")
        self.assertEqual(self.statuses.first_after_start.association_candidates, stored_candidates,
                         "association candidates lost by the kill")
        # Replay the whole bag: frames already in the dataset are not added twice.
        self.play()
        self.assertTrue(wait_for(lambda: self.statuses.last.state_name == "done"),
                        "not done: %s" % self.statuses.last)
        with open(self.result_file) as f:
            result = yaml.safe_load(f)
        self.assertEqual(result["pairs_by_rule"]["counts"], required)
        stamps = [p["stamp"] for p in result["pairs"]]
        self.assertEqual(len(stamps), len(set(stamps)), "a pair was added twice")
        # The replay from the start offers the frames the first run skipped again: none becomes a
        # pair next to a stored one (the skip rule keeps pairs 4 frames, 0.4 s, apart).
        counts = sorted(p["stamp"] for p in result["pairs"] if p["rule"] == "counts")
        gaps = [b - a for a, b in zip(counts, counts[1:])]
        self.assertGreater(min(gaps), 0.35, "pairs closer than the skip rule keeps them")
        self.assertEqual(self.statuses.last.pairs_resumed, resumed)
        # Candidates from before the kill were paired by association in the resumed fit.
        early = [p for p in result["pairs"] if p["rule"] == "association" and p["stamp"] <= killed_at + 1e-6]
        self.assertGreater(len(early), 0, "no association pair from the candidates stored before the kill")
        # ~save's account of the bag counts both, from the file.
        _, candidates_now, _ = stored_frames(self.dataset_bag)
        rospy.wait_for_service(NODE + "/save", timeout=HANG_GUARD_S)
        saved = rospy.ServiceProxy(NODE + "/save", Trigger)()
        self.assertTrue(saved.success, saved.message)
        self.assertIn("and %d association candidates" % candidates_now, saved.message)
        # calibrate_bag on the dataset bag reads it as ~resume does: every stored pair and candidate,
        # and so the node's result again, association pairs included, when the bag holds what the
        # fit had (frames that finish while it runs are recorded too, as many as the replay had
        # sent by then: on a loaded machine some).
        stored_pairs, stored_candidates_end, stored_skipped_end, _ = stored_frames(self.dataset_bag, True)
        again = os.path.join(self.work, "calibrate_bag.yaml")
        args = [executable("calibrate_bag"), "--bag", self.dataset_bag, "--output", again, "--quiet"]
        for path in rospy.get_param("~config_files").split()[1:]:  # the first is the defaults
            args += ["--config", path]
        with open(os.path.join(self.work, "calibrate_bag.log"), "w") as log:
            subprocess.run(args, check=True, stdout=log, stderr=subprocess.STDOUT)
        with open(again) as f:
            rerun = yaml.safe_load(f)
        self.assertEqual(rerun["pairs_by_rule"]["counts"], stored_pairs)
        self.assertEqual(rerun["association"]["candidate_frames"], stored_candidates_end)
        self.assertEqual(rerun["association"]["skipped_frames"], stored_skipped_end)
        self.assertGreater(stored_skipped_end, 0, "no skipped frame in the dataset bag (final round)")
        same_input = (stored_pairs == result["pairs_by_rule"]["counts"] and
                      stored_candidates_end == result["association"]["candidate_frames"] and
                      stored_skipped_end == result["association"]["skipped_frames"])
        if same_input:
            self.assertEqual(rerun["pairs_by_rule"], result["pairs_by_rule"])
            for key in ("rotation_vector", "translation"):
                for a, b in zip(rerun[key], result[key]):
                    self.assertAlmostEqual(a, b, places=9, msg=key)
            # Judged alike: the velocities' errors come back with them (velocity_fields.hpp).
            self.assertAlmostEqual(rerun["timing"]["resolution_ms"], result["timing"]["resolution_ms"], places=6)
            self.assertEqual(rerun["verdict"], result["verdict"])
            self.assertEqual(rerun["verdict_reasons"], result["verdict_reasons"])
        else:
            node_pairs = set(p["stamp"] for p in result["pairs"] if p["rule"] == "counts")
            rerun_pairs = set(p["stamp"] for p in rerun["pairs"] if p["rule"] == "counts")
            self.assertTrue(node_pairs <= rerun_pairs, "a pair of the node's fit is not in the bag")
        rospy.loginfo("calibrate_bag on the dataset bag: %d pairs, %d candidates, %d skipped frames (the node's "
                      "fit: %d, %d, %d)%s", stored_pairs, stored_candidates_end, stored_skipped_end,
                      result["pairs_by_rule"]["counts"], result["association"]["candidate_frames"],
                      result["association"]["skipped_frames"], ", the same result" if same_input else "")
        rospy.loginfo("resumed %d pairs and %d candidates (%d pairs kept before the kill), finished with %d, "
                      "%d association pairs from before the kill", resumed, stored_candidates, kept_before,
                      result["pairs_by_rule"]["counts"], len(early))


    def test_resumed_fit_starts_from_the_tf(self):
        """~resume with ~initial_from_tf: the resumed dataset (pairs_required pairs already) is
        fitted once the tf between the two frames is in the tree, and association starts from it."""
        required = rospy.get_param(NODE + "/pairs_required")
        node = self.start_node()
        self.play()
        self.assertTrue(wait_for(lambda: self.statuses.last.state_name == "done"),
                        "not done: %s" % self.statuses.last)
        node.send_signal(signal.SIGINT)
        node.wait()
        os.remove(self.result_file)
        self.assertGreaterEqual(stored_frames(self.dataset_bag)[0], required)

        with open(os.path.join(self.work, "truth.yaml")) as f:
            truth = yaml.safe_load(f)
        broadcaster = tf2_ros.StaticTransformBroadcaster()
        broadcaster.sendTransform(camera_in_lidar(truth))  # latched: there before the node starts
        rospy.set_param(NODE + "/resume", True)
        rospy.set_param(NODE + "/initial_from_tf", True)
        # The fit starts as soon as the tf is found; this bound only ends a wait for a missing one.
        rospy.set_param(NODE + "/tf_check_wait_s", 60.0)
        self.start_node()
        self.assertTrue(wait_for(lambda: self.statuses.last.state_name == "done"),
                        "not done: %s" % self.statuses.last)
        with open(self.result_file) as f:
            result = yaml.safe_load(f)
        self.assertEqual(self.statuses.last.pairs_resumed, result["pairs_by_rule"]["counts"])
        self.assertTrue(result["association"]["initial_extrinsic_used"], result["association"])


def camera_in_lidar(truth):
    """The truth (p_C = R p_L + t) as tf has it: the camera's pose in the LiDAR frame."""
    r = truth["rotation_matrix"]
    t = truth["translation"]
    rt = [[r[0], r[3], r[6]], [r[1], r[4], r[7]], [r[2], r[5], r[8]]]  # R^T
    msg = TransformStamped()
    msg.header.stamp = rospy.Time.now()
    msg.header.frame_id = truth["lidar_frame"]
    msg.child_frame_id = truth["camera_frame"]
    origin = [-sum(rt[i][k] * t[k] for k in range(3)) for i in range(3)]
    msg.transform.translation.x, msg.transform.translation.y, msg.transform.translation.z = origin
    x, y, z, w = truth["quaternion_xyzw"]  # of R; R^T is its conjugate
    msg.transform.rotation.x, msg.transform.rotation.y, msg.transform.rotation.z = -x, -y, -z
    msg.transform.rotation.w = w
    return msg


if __name__ == "__main__":
    rospy.init_node("test_node_resume")
    rostest.rosrun("thermal_lidar_calibration", "node_resume", KillAndResume)
