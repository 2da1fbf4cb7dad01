// calibration_node's parameters: core keys through the shared table, node-only keys here.

#include "thermal_lidar_calibration/node/node_parameters.hpp"
#include "thermal_lidar_calibration/ros/node_parameter_source.hpp"
#include "thermal_lidar_calibration/app/parameter_readers.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace thermal_lidar_calibration {
namespace ros_io {

NodeParameters loadNodeParameters(const ros::NodeHandle& private_nh) {
  const auto source = makeNodeHandleParameterSource(private_nh);
  NodeParameters p;
  p.core = loadCoreParameters(*source);
  readStringParameter(*source, "output_file", p.output_file);
  readStringParameter(*source, "dataset_bag", p.dataset_bag);
  readBoolParameter(*source, "resume", p.resume);
  readStringParameter(*source, "camera_info_file", p.camera_info_file);
  readStringParameter(*source, "child_frame", p.child_frame);
  // pairs_required is range-checked by the core table; the minimum must not exceed it.
  readIntParameter(*source, "min_pairs_to_calibrate", 1, p.core.pairs_required, p.min_pairs_to_calibrate);
  if (!source->has("min_pairs_to_calibrate") && p.min_pairs_to_calibrate > p.core.pairs_required) {
    p.min_pairs_to_calibrate = p.core.pairs_required;
  }
  readDoubleParameter(*source, "progress_log_period_s", 0.0, true, 3600.0, p.progress_log_period_s);
  readDoubleParameter(*source, "status_rate_hz", 0.1, false, 100.0, p.status_rate_hz);
  readDoubleParameter(*source, "tf_check_wait_s", 0.0, false, 60.0, p.tf_check_wait_s);
  readIntParameter(*source, "overlay_max_points", 100, 10000000, p.overlay_max_points);
  if (p.output_file.empty()) {
    throw std::invalid_argument("parameter 'output_file' = '': must name the result YAML file");
  }
  if (p.resume && p.dataset_bag.empty()) {
    throw std::invalid_argument(
        "parameter 'resume' = true but 'dataset_bag' is empty: name the dataset bag to resume");
  }
  return p;
}

std::vector<std::pair<std::string, std::string>> describeNodeParameters(const NodeParameters& p) {
  return {{"output_file", p.output_file},
          {"dataset_bag", p.dataset_bag.empty() ? "'' (not recorded)" : p.dataset_bag},
          {"resume", p.resume ? "true" : "false"},
          {"camera_info_file", p.camera_info_file.empty() ? "'' (use the topic)"
                                                          : p.camera_info_file},
          {"child_frame", p.child_frame.empty() ? "'' (<camera_frame>_calibrated)" : p.child_frame},
          {"min_pairs_to_calibrate", std::to_string(p.min_pairs_to_calibrate)},
          {"progress_log_period_s", formatParameterNumber(p.progress_log_period_s)},
          {"status_rate_hz", formatParameterNumber(p.status_rate_hz)},
          {"tf_check_wait_s", formatParameterNumber(p.tf_check_wait_s)},
          {"overlay_max_points", std::to_string(p.overlay_max_points)}};
}

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
