#pragma once
// The truth YAML of a make_synthetic_bag run: the INTERFACE extrinsic keys (p_C = R p_L + t) of
// the true extrinsic, the frames, and how the drive was made (rig, seed, noise, intrinsics).

#include "thermal_lidar_calibration/synthetic/synthetic_rig.hpp"
#include "thermal_lidar_calibration/tools/make_synthetic_bag_options.hpp"

#include <string>

namespace thermal_lidar_calibration {
namespace ros_io {

// Throws std::runtime_error when the file cannot be written.
void writeSyntheticTruth(const MakeSyntheticBagOptions& options, const synthetic::SyntheticRig& rig);

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
