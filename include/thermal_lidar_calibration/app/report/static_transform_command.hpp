#pragma once
// The command line that republishes a result with tf2_ros's own tool, printed by calibrate_bag
// and logged by calibration_node so a user can pin the result without this package.

#include "thermal_lidar_calibration/core/extrinsic.hpp"

#include <string>

namespace thermal_lidar_calibration {

// "rosrun tf2_ros static_transform_publisher x y z qx qy qz qw <lidar_frame> <child_frame>":
// tf's transform is the pose of the child (camera) in the parent (LiDAR), the inverse of
// p_C = R p_L + t.
std::string staticTransformPublisherCommand(const Extrinsic& extrinsic,
                                            const std::string& lidar_frame,
                                            const std::string& child_frame);

}  // namespace thermal_lidar_calibration
