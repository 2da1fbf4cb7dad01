"""The package's built executables for the Python rostests (imported from this folder)."""
import subprocess

PKG = "thermal_lidar_calibration"


def executable(name):
    """The path of `name` (catkin_find, as play_synthetic_bag.sh finds the generator: rosrun would
    walk the whole checkout, the catkin workspace in it included, at every start)."""
    return subprocess.check_output(["catkin_find", "--first-only", "--libexec", PKG, name],
                                   universal_newlines=True).strip()
