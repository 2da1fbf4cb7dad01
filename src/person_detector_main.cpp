// thermal_person_segmenter and lidar_person_detector: one main, the node chosen at build time
// (TLC_DETECTOR_NODE); see include/thermal_lidar_calibration/node/person_detector_nodes.hpp.
#include "thermal_lidar_calibration/node/person_detector_nodes.hpp"

#include <memory>

#ifndef TLC_DETECTOR_NODE
#error "TLC_DETECTOR_NODE must name the node class"
#endif
#ifndef TLC_DETECTOR_NAME
#error "TLC_DETECTOR_NAME must be the node's name"
#endif

int main(int argc, char** argv) {
  ros::init(argc, argv, TLC_DETECTOR_NAME);
  ros::NodeHandle nh, private_nh("~");
  std::unique_ptr<thermal_lidar_calibration::ros_io::TLC_DETECTOR_NODE> node;
  try {
    node = std::make_unique<thermal_lidar_calibration::ros_io::TLC_DETECTOR_NODE>(nh, private_nh);
  } catch (const std::exception& e) {
    ROS_FATAL("%s cannot start: %s", TLC_DETECTOR_NAME, e.what());
    return 1;
  }
  ros::spin();  // the callbacks catch their own exceptions
  return 0;
}
