#pragma once
// calibration_node's parameters: the core keys shared with calibrate_bag plus the node-only
// keys (their rows: src/app/parameters/node_parameter_table.cpp, same machinery as the core table).
// ROS-free: the node reads them through a ParameterSource over its private NodeHandle.

#include "thermal_lidar_calibration/app/parameters/core_parameters.hpp"

#include <string>
#include <utility>
#include <vector>

namespace thermal_lidar_calibration {

// ~mode: collect pairs and optimize, or watch the extrinsic in use for drift (issue 9).
enum class NodeMode { kCalibrate, kMonitor };

// ~stop_when: optimize once at ~pairs_required, or again and again until the verdict is good.
enum class StopWhen { kPairs, kQuality };

struct NodeParameters {
  CoreParameters core;
  NodeMode mode = NodeMode::kCalibrate;
  bool monitor_after_calibration = false;  // after a calibration, watch its result for drift
  bool auto_update = false;          // publish and write a confirmed new extrinsic unasked
  StopWhen stop_when = StopWhen::kPairs;
  int quality_check_every_pairs = 10;  // stop_when quality: optimize again after this many new pairs
  int max_pairs = 200;                 // stop_when quality: the last fit, good or not
  std::string output_file = "thermal_lidar_calibration.yaml";  // relative to ROS_HOME
  std::string dataset_bag = "thermal_lidar_dataset.bag";       // "" = do not record pairs
  bool resume = false;               // reload dataset_bag at start and continue it
  std::string camera_info_file;      // camera_calibration YAML; "" = use thermal/camera_info
  std::string reference_file;        // result YAML of the calibration in use; "" = none
  std::string report_dir;            // visual report after each calibration; "" = none
  std::string child_frame;           // used when the camera frame already has a parent;
                                     // "" = "<camera_frame>_calibrated"
  int min_pairs_to_calibrate = 20;   // ~calibrate is refused below this, [1, pairs_required]
  double progress_log_period_s = 5.0;  // (0, 3600]
  double fault_log_period_s = 5.0;     // (0, 3600]: one warning per kind of fault and period
  double status_rate_hz = 2.0;         // [0.1, 100]; ~status also goes out on every change
  double tf_check_wait_s = 2.0;        // [0, 60]: listen to /tf, /tf_static before publishing
  int overlay_max_points = 30000;      // [100, 10000000] points drawn per overlay image
  // Issue 23: frames held for pairing by association, at most (each holds its decoded image).
  int association_max_candidates = 300;
  // Issue 23: start association from the tf between the LiDAR and the camera frame (if the count
  // rule's pairs agree with it) instead of the first fit; exclusive with initial_extrinsic_file.
  bool initial_from_tf = false;
};

// Its rows (node_parameter_table.cpp) and the rules across keys that follow them; with these,
// parameterTable<>, loadParameters<> and describeParameters (parameter_table.hpp) serve this
// struct, and the named forms below are theirs.
template <>
ParameterTable<NodeParameters> makeParameterTable();
template <>
void finishLoading(const ParameterSource& source, NodeParameters& params);

inline const ParameterTable<NodeParameters>& nodeParameterTable() {
  return parameterTable<NodeParameters>();
}
// Node-only keys, then the core keys and the node's cross-key rules. Throws std::invalid_argument
// naming the key, the value and the allowed range; the node refuses to start.
inline NodeParameters loadNodeParameters(const ParameterSource& source) {
  return loadParameters<NodeParameters>(source);
}
// "key: value" for every node-only key (the core keys come from describeCoreParameters).
inline std::vector<std::pair<std::string, std::string>> describeNodeParameters(const NodeParameters& p) {
  return describeParameters(p);
}

}  // namespace thermal_lidar_calibration
