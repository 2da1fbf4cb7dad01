#!/usr/bin/env python3
"""Fails when a ROS-free part of the package reaches a ROS header, directly or through others.

Debian installs ROS headers in /usr/include, so a ROS include in src/core compiles whatever the
target's include paths say. This check runs the preprocessor on every source and header of the
ROS-free parts (core, app, synthetic, detection, detection_tool: src/<part>/ and
include/thermal_lidar_calibration/<part>/) with only the include paths those parts use, lists
every header each one reaches (g++ -H), and reports the include chain to the first ROS header:

  src/core/foo.cpp -> include/thermal_lidar_calibration/core/foo.hpp -> /usr/include/ros/time.h

A header is a ROS header when it lies in an include directory named after a ROS package
(/usr/include/<pkg>/ with /usr/share/<pkg>/package.xml, or ros/), in the devel space's include
directory (generated messages), or in this package's adapter folders (ros/, node/, tools/).
--self-test first checks that planted includes are caught, so the check cannot go blind.

Usage: check_ros_free.py PACKAGE_SOURCE_DIR [--devel-include DIR] [--compiler CXX] [--self-test]
"""

import argparse
import concurrent.futures
import glob
import os
import re
import subprocess
import sys
import tempfile

ROS_FREE_PARTS = ["core", "app", "synthetic", "detection", "detection_tool"]
ADAPTER_PARTS = ["ros", "node", "tools"]
PACKAGE = "thermal_lidar_calibration"
EXTENSIONS = (".cpp", ".cc", ".hpp", ".h")


def ros_package_names():
    names = {"ros"}  # roscpp, rostime, rosconsole install their headers under ros/
    for xml in glob.glob("/usr/share/*/package.xml"):
        names.add(os.path.basename(os.path.dirname(xml)))
    for root in os.environ.get("ROS_PACKAGE_PATH", "").split(":"):
        for xml in glob.glob(os.path.join(root, "*", "package.xml")):
            names.add(os.path.basename(os.path.dirname(xml)))
    names.discard(PACKAGE)  # our own headers are judged by folder below
    return names


class Checker:
    def __init__(self, source_dir, devel_include, compiler):
        self.source_dir = os.path.abspath(source_dir)
        self.devel_include = os.path.abspath(devel_include) if devel_include else None
        self.compiler = compiler
        self.ros_names = ros_package_names()
        self.own_include = os.path.join(self.source_dir, "include", PACKAGE)
        self.include_flags = ["-I" + os.path.join(self.source_dir, "include")]
        if self.devel_include:
            self.include_flags.append("-I" + self.devel_include)  # so generated msgs are found
        for pattern in ["/usr/include/eigen3", "/usr/include/opencv4", "/usr/include/pcl-*"]:
            self.include_flags += ["-I" + d for d in sorted(glob.glob(pattern))]

    def why_ros(self, header):
        """The reason `header` is a ROS header, or None."""
        path = os.path.normpath(os.path.abspath(header))
        if self.devel_include and path.startswith(self.devel_include + os.sep):
            return "generated ROS message header"
        if path.startswith(self.own_include + os.sep):
            part = path[len(self.own_include) + 1:].split(os.sep)[0]
            return "this package's ROS side (%s/)" % part if part in ADAPTER_PARTS else None
        match = re.match(r"^/usr/(?:local/)?include/([^/]+)/", path)
        if match and match.group(1) in self.ros_names:
            return "ROS package %s" % match.group(1)
        return None

    def check_file(self, path):
        """None when clean, else a one-line report."""
        if self.why_ros(path):
            return "%s is itself on the ROS side" % path
        # -fdirectives-only: the includes and conditionals are processed as usual (the same
        # headers are listed) but macros are not expanded in the text: a quarter of the CPU time.
        cmd = [self.compiler, "-std=c++17", "-fopenmp", "-x", "c++", "-E", "-fdirectives-only", "-H",
               "-o", os.devnull]
        cmd += self.include_flags + [path]
        proc = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                              universal_newlines=True)
        chain = [path]
        for line in proc.stderr.splitlines():
            match = re.match(r"^(\.+) (.+)$", line)
            if not match:
                continue
            depth, header = len(match.group(1)), match.group(2)
            del chain[depth:]
            chain.append(header)
            reason = self.why_ros(header)
            if reason:
                return "%s reaches a ROS header (%s): %s" % (
                    self.relative(path), reason, " -> ".join(self.relative(h) for h in chain))
        if proc.returncode != 0:
            errors = [l for l in proc.stderr.splitlines() if "error" in l]
            return "%s cannot be preprocessed: %s" % (self.relative(path), "; ".join(errors[:3]))
        return None

    def relative(self, path):
        path = os.path.normpath(path)
        return os.path.relpath(path, self.source_dir) if path.startswith(self.source_dir) else path

    def files(self, parts):
        found = []
        for part in parts:
            for top in [os.path.join(self.source_dir, "src", part), os.path.join(self.own_include, part)]:
                for root, _, names in os.walk(top):
                    found += [os.path.join(root, n) for n in sorted(names) if n.endswith(EXTENSIONS)]
        return sorted(found)

    def run(self, parts):
        files = self.files(parts)
        with concurrent.futures.ThreadPoolExecutor(max_workers=os.cpu_count() or 2) as pool:
            reports = [r for r in pool.map(self.check_file, files) if r]
        return files, reports


def self_test(compiler, devel_include):
    """Plants a direct and an indirect ROS include in a scratch package: both must be caught."""
    with tempfile.TemporaryDirectory(prefix="tlc_ros_free_selftest_") as tmp:
        core_inc = os.path.join(tmp, "include", PACKAGE, "core")
        ros_inc = os.path.join(tmp, "include", PACKAGE, "ros")
        core_src = os.path.join(tmp, "src", "core")
        for d in (core_inc, ros_inc, core_src):
            os.makedirs(d)
        files = {
            os.path.join(core_src, "direct.cpp"): "#include <vector>\n#include <ros/time.h>\n",
            os.path.join(core_inc, "indirect.hpp"): "#include <Eigen/Core>\n#include <std_msgs/Header.h>\n",
            os.path.join(core_src, "via_header.cpp"): '#include "%s/core/indirect.hpp"\n' % PACKAGE,
            os.path.join(ros_inc, "adapter.hpp"): "#include <string>\n",
            os.path.join(core_src, "via_adapter.cpp"): '#include "%s/ros/adapter.hpp"\n' % PACKAGE,
            os.path.join(core_src, "clean.cpp"): "#include <Eigen/Core>\n#include <opencv2/core.hpp>\n",
        }
        for path, text in files.items():
            with open(path, "w") as f:
                f.write(text)
        _, reports = Checker(tmp, devel_include, compiler).run(["core"])
        caught = {os.path.basename(r.split(" ")[0]) for r in reports}
        expected = {"direct.cpp", "indirect.hpp", "via_header.cpp", "via_adapter.cpp"}
        if caught != expected:
            print("self-test FAILED: planted includes caught in %s, expected %s\n  %s"
                  % (sorted(caught), sorted(expected), "\n  ".join(reports)))
            return False
        print("self-test: the planted ROS includes (direct, through a header, through an "
              "adapter header) are caught")
        return True


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("source_dir")
    parser.add_argument("--devel-include", default=None)
    parser.add_argument("--compiler", default="g++")
    parser.add_argument("--self-test", action="store_true")
    args = parser.parse_args()
    if args.self_test and not self_test(args.compiler, args.devel_include):
        return 1
    checker = Checker(args.source_dir, args.devel_include, args.compiler)
    parts = [p for p in ROS_FREE_PARTS
             if os.path.isdir(os.path.join(args.source_dir, "src", p))
             or os.path.isdir(os.path.join(checker.own_include, p))]
    files, reports = checker.run(parts)
    if not files:
        print("no files found under the ROS-free parts of %s" % args.source_dir)
        return 1
    for report in reports:
        print("FAIL: " + report)
    print("%d files of %s checked, %d reach ROS" % (len(files), ", ".join(parts), len(reports)))
    return 1 if reports else 0


if __name__ == "__main__":
    sys.exit(main())
