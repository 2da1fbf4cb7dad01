#!/usr/bin/env python3
"""calibration.launch gives calibration_node OMP_WAIT_POLICY: PASSIVE unless the caller's
environment or the omp_wait_policy argument says otherwise (docs/validation/performance.md:
spinning OpenMP threads took 2-3x the CPU time on a busy machine). Loads the launch file as
roslaunch does, without starting anything, and reads the node's environment.

Usage: check_launch_env.py LAUNCH_FILE"""
import os
import sys

import roslaunch.config
import roslaunch.xmlloader


def node_env(launch_file, args, environment):
    """The calibration node's environment entries for launch arguments `args` (name: value)
    with OMP_WAIT_POLICY set to `environment` in the caller's environment (None: unset)."""
    saved = os.environ.get("OMP_WAIT_POLICY")
    try:
        if environment is None:
            os.environ.pop("OMP_WAIT_POLICY", None)
        else:
            os.environ["OMP_WAIT_POLICY"] = environment
        config = roslaunch.config.ROSLaunchConfig()
        loader = roslaunch.xmlloader.XmlLoader()
        argv = ["%s:=%s" % kv for kv in args.items()]
        loader.load(launch_file, config, argv=argv, verbose=False)
    finally:
        if saved is None:
            os.environ.pop("OMP_WAIT_POLICY", None)
        else:
            os.environ["OMP_WAIT_POLICY"] = saved
    nodes = [n for n in config.nodes if n.type == "calibration_node"]
    if len(nodes) != 1:
        raise AssertionError("expected one calibration_node in %s, found %d" % (launch_file, len(nodes)))
    return dict(nodes[0].env_args)


def main():
    launch_file = sys.argv[1]
    cases = [
        ({}, None, "PASSIVE"),                              # the default
        ({}, "ACTIVE", "ACTIVE"),                           # the caller's environment wins
        ({"omp_wait_policy": "ACTIVE"}, None, "ACTIVE"),    # so does the argument
        ({"omp_wait_policy": "PASSIVE"}, "ACTIVE", "PASSIVE"),
    ]
    failures = 0
    for args, environment, expected in cases:
        got = node_env(launch_file, args, environment).get("OMP_WAIT_POLICY")
        if got != expected:
            failures += 1
            print("FAIL: args %s, environment OMP_WAIT_POLICY=%s: the node gets %s, expected %s"
                  % (args, environment, got, expected))
    print("%d of %d cases as expected" % (len(cases) - failures, len(cases)))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
