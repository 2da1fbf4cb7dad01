#pragma once
// A ParameterSource over a node's private parameters (~key), for calibration_node.

#include "thermal_lidar_calibration/app/parameters/parameter_source.hpp"

#include <ros/node_handle.h>

#include <memory>
#include <string>
#include <vector>

namespace thermal_lidar_calibration {
namespace ros_io {

// Reads `key` as private_nh.getParam(key). Integers are accepted where a double is expected;
// a double is never accepted as an integer.
std::unique_ptr<ParameterSource> makeNodeHandleParameterSource(const ros::NodeHandle& private_nh);

// The keys set directly under the node's private namespace (for the typo warning with
// unknownParameterKeys()).
std::vector<std::string> nodeParameterKeys(const ros::NodeHandle& private_nh);

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
