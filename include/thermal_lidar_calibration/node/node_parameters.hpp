#pragma once
// calibration_node's parameters: the core keys shared with calibrate_bag plus the node-only
// keys. Loaded once at start; any invalid value throws std::invalid_argument naming the key,
// the value and the allowed range, and the node refuses to start.

#include "thermal_lidar_calibration/app/parameters.hpp"

#include <ros/node_handle.h>

#include <string>
#include <utility>
#include <vector>

namespace thermal_lidar_calibration {
namespace ros_io {

struct NodeParameters {
  CoreParameters core;
  std::string output_file = "thermal_lidar_calibration.yaml";  // relative to ROS_HOME
  std::string dataset_bag = "thermal_lidar_dataset.bag";       // "" = do not record pairs
  bool resume = false;               // reload dataset_bag at start and continue it
  std::string camera_info_file;      // camera_calibration YAML; "" = use thermal/camera_info
  std::string child_frame;           // used when the camera frame already has a parent;
                                     // "" = "<camera_frame>_calibrated"
  int min_pairs_to_calibrate = 20;   // ~calibrate is refused below this, [1, pairs_required]
  double progress_log_period_s = 5.0;  // (0, 3600]
  double status_rate_hz = 2.0;         // [0.1, 100]; ~status also goes out on every change
  double tf_check_wait_s = 2.0;        // [0, 60]: listen to /tf, /tf_static before publishing
  int overlay_max_points = 30000;      // [100, 10000000] points drawn per overlay image
};

// Reads ~ parameters of `private_nh`. Throws std::invalid_argument on any invalid value.
NodeParameters loadNodeParameters(const ros::NodeHandle& private_nh);
// "key: value" for every node-only key (the core keys come from describeCoreParameters). Its
// keys are also the node-only part of knownParameterKeys().
std::vector<std::pair<std::string, std::string>> describeNodeParameters(const NodeParameters& p);

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
