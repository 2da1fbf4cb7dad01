#!/usr/bin/env python3
"""calibration_node checks the files it will write at start (issue 12, item 5): an unwritable
~output_file or ~dataset_bag makes it refuse to start with one line that names the key and the
path, instead of failing an hour later when the first pair is kept.

Runs under rostest (node_start_checks.test) with param ~work_dir.
"""
import os
import shutil
import subprocess
import unittest

import rospy
import rostest

from package_executables import executable

PKG = "thermal_lidar_calibration"


class StartChecks(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("node_start_checks")
        cls.work = rospy.get_param("~work_dir")
        shutil.rmtree(cls.work, ignore_errors=True)
        os.makedirs(cls.work)

    def start(self, name, **params):
        """Runs the node with private params; returns (exit code, output) or fails on a hang."""
        args = [executable("calibration_node"), "__name:=" + name]
        args += ["_%s:=%s" % (k, v) for k, v in params.items()]
        try:
            done = subprocess.run(args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                  timeout=30, universal_newlines=True)
        except subprocess.TimeoutExpired:
            self.fail("calibration_node %s started with %s (should have refused)" % (name, params))
        return done.returncode, done.stdout

    def fatal_line(self, output):
        """The one line saying why the node cannot start."""
        fatal = [line for line in output.splitlines() if "cannot start" in line]
        self.assertEqual(len(fatal), 1, output)
        return fatal[0]

    def assert_refused(self, output, key, path, reason):
        fatal = self.fatal_line(output)
        self.assertIn("parameter '%s' = %s" % (key, path), fatal)
        self.assertIn(reason, fatal)

    def test_output_file_in_a_missing_directory(self):
        path = os.path.join(self.work, "missing", "result.yaml")
        code, out = self.start("bad_output", output_file=path,
                               dataset_bag=os.path.join(self.work, "d1.bag"))
        self.assertNotEqual(code, 0, out)
        self.assert_refused(out, "output_file", path, "does not exist")

    def test_dataset_bag_under_a_plain_file(self):
        plain = os.path.join(self.work, "plain")
        with open(plain, "w") as f:
            f.write("not a directory\n")
        path = os.path.join(plain, "dataset.bag")
        code, out = self.start("bad_bag", output_file=os.path.join(self.work, "r2.yaml"),
                               dataset_bag=path)
        self.assertNotEqual(code, 0, out)
        self.assert_refused(out, "dataset_bag", path, "is not a directory")

    def test_dataset_bag_where_no_file_can_be_made(self):
        path = "/proc/tlc_dataset.bag"  # no new files in /proc, not even for root
        code, out = self.start("proc_bag", output_file=os.path.join(self.work, "r3.yaml"),
                               dataset_bag=path)
        self.assertNotEqual(code, 0, out)
        self.assert_refused(out, "dataset_bag", path, "cannot create files in /proc")

    def test_unreadable_reference_file(self):
        path = os.path.join(self.work, "no_such_result.yaml")
        code, out = self.start("bad_reference", output_file=os.path.join(self.work, "r4.yaml"),
                               dataset_bag="", reference_file=path)
        self.assertNotEqual(code, 0, out)
        fatal = self.fatal_line(out)
        self.assertIn("parameter 'reference_file'", fatal)
        self.assertIn(path, fatal)

    def test_unreadable_initial_extrinsic_file(self):
        # Read at start (issue 23), as calibrate_bag reads it before the bag: not at the first fit.
        path = os.path.join(self.work, "no_such_start.yaml")
        code, out = self.start("bad_initial", output_file=os.path.join(self.work, "r5.yaml"),
                               dataset_bag="", initial_extrinsic_file=path)
        self.assertNotEqual(code, 0, out)
        fatal = self.fatal_line(out)
        self.assertIn("parameter 'initial_extrinsic_file'", fatal)
        self.assertIn(path, fatal)

    def test_initial_from_tf_with_an_initial_extrinsic_file(self):
        path = os.path.join(self.work, "start.yaml")
        code, out = self.start("two_starts", output_file=os.path.join(self.work, "r6.yaml"),
                               dataset_bag="", initial_extrinsic_file=path, initial_from_tf="true")
        self.assertNotEqual(code, 0, out)
        fatal = self.fatal_line(out)
        self.assertIn("'initial_from_tf' = true and 'initial_extrinsic_file'", fatal)


if __name__ == "__main__":
    rostest.rosrun(PKG, "node_start_checks", StartChecks)
