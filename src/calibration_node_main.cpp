// calibration_node: see include/thermal_lidar_calibration/node/calibration_node.hpp and README.md.
#include "thermal_lidar_calibration/node/calibration_node.hpp"

#include <memory>

int main(int argc, char** argv) {
  ros::init(argc, argv, "calibration_node");
  ros::NodeHandle nh, private_nh("~");  // outlive the node: a start-up error can still be logged
  std::unique_ptr<thermal_lidar_calibration::ros_io::CalibrationNode> node;
  try {
    node = std::make_unique<thermal_lidar_calibration::ros_io::CalibrationNode>(nh, private_nh);
  } catch (const std::exception& e) {
    ROS_FATAL("calibration_node cannot start: %s", e.what());
    return 1;
  }
  // The node's callbacks catch their own exceptions; this is the last line of defence, so that
  // nothing that arrives ends a node that runs beside a vehicle's stack for hours.
  while (ros::ok()) {
    try {
      ros::spin();
    } catch (const std::exception& e) {
      ROS_ERROR("calibration_node: a callback failed: %s; the node keeps running", e.what());
    }
  }
  return 0;
}
