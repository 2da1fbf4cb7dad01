// calibration_node: see include/thermal_lidar_calibration/node/calibration_node.hpp and README.md.
#include "thermal_lidar_calibration/node/calibration_node.hpp"

int main(int argc, char** argv) {
  ros::init(argc, argv, "calibration_node");
  ros::NodeHandle nh, private_nh("~");  // outlive the node: a start-up error can still be logged
  try {
    thermal_lidar_calibration::ros_io::CalibrationNode node(nh, private_nh);
    ros::spin();
  } catch (const std::exception& e) {
    ROS_FATAL("calibration_node cannot start: %s", e.what());
    return 1;
  }
  return 0;
}
