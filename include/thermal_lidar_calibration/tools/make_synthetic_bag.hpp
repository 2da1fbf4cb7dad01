#pragma once
// make_synthetic_bag: renders a synthetic drive (ROS-free rig, frames in parallel batches),
// writes it with SyntheticBagWriter and the truth YAML, and prints what a consumer will keep.

#include "thermal_lidar_calibration/tools/make_synthetic_bag_options.hpp"

namespace thermal_lidar_calibration {
namespace ros_io {

// Returns the exit code (0). Throws std::invalid_argument for settings the rig refuses, other
// exceptions for failures while writing.
int runMakeSyntheticBag(const MakeSyntheticBagOptions& options);

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
