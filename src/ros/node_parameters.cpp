// calibration_node's parameters: core keys through the shared table, node-only keys here.

#include "thermal_lidar_calibration/ros/node_parameters.hpp"
#include "thermal_lidar_calibration/ros/node_parameter_source.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace thermal_lidar_calibration {
namespace ros_io {
namespace {

std::string formatDouble(double v) {
  std::ostringstream s;
  s.precision(12);
  s << v;
  return s.str();
}

std::string rawValue(const ParameterSource& source, const std::string& key) {
  if (auto i = source.getInt(key)) return std::to_string(*i);
  if (auto d = source.getDouble(key)) return formatDouble(*d);
  if (auto b = source.getBool(key)) return *b ? "true" : "false";
  if (auto s = source.getString(key)) return "'" + *s + "'";
  return "<not a scalar>";
}

[[noreturn]] void bad(const ParameterSource& source, const std::string& key,
                      const std::string& requirement) {
  throw std::invalid_argument("parameter '" + key + "' = " + rawValue(source, key) + ": " +
                              requirement);
}

void readString(const ParameterSource& source, const std::string& key, std::string& target) {
  if (!source.has(key)) return;
  const auto v = source.getString(key);
  if (!v) bad(source, key, "must be a string");
  target = *v;
}

void readBool(const ParameterSource& source, const std::string& key, bool& target) {
  if (!source.has(key)) return;
  const auto v = source.getBool(key);
  if (!v) bad(source, key, "must be true or false");
  target = *v;
}

void readInt(const ParameterSource& source, const std::string& key, long long lo, long long hi,
             int& target) {
  if (!source.has(key)) return;
  const auto v = source.getInt(key);
  if (!v || *v < lo || *v > hi) {
    bad(source, key,
        "must be an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  }
  target = static_cast<int>(*v);
}

// [lo, hi], or (lo, hi] when lo_open.
void readDouble(const ParameterSource& source, const std::string& key, double lo, bool lo_open,
                double hi, double& target) {
  if (!source.has(key)) return;
  const auto v = source.getDouble(key);
  if (!v || !std::isfinite(*v) || *v > hi || (lo_open ? *v <= lo : *v < lo)) {
    bad(source, key,
        "must be a number in " + std::string(lo_open ? "(" : "[") + formatDouble(lo) + ", " +
            formatDouble(hi) + "]");
  }
  target = *v;
}

}  // namespace

NodeParameters loadNodeParameters(const ros::NodeHandle& private_nh) {
  const auto source = makeNodeHandleParameterSource(private_nh);
  NodeParameters p;
  p.core = loadCoreParameters(*source);
  readString(*source, "output_file", p.output_file);
  readString(*source, "dataset_bag", p.dataset_bag);
  readBool(*source, "resume", p.resume);
  readString(*source, "camera_info_file", p.camera_info_file);
  readString(*source, "child_frame", p.child_frame);
  // pairs_required is range-checked by the core table; the minimum must not exceed it.
  readInt(*source, "min_pairs_to_calibrate", 1, p.core.pairs_required, p.min_pairs_to_calibrate);
  if (!source->has("min_pairs_to_calibrate") && p.min_pairs_to_calibrate > p.core.pairs_required) {
    p.min_pairs_to_calibrate = p.core.pairs_required;
  }
  readDouble(*source, "progress_log_period_s", 0.0, true, 3600.0, p.progress_log_period_s);
  readDouble(*source, "status_rate_hz", 0.1, false, 100.0, p.status_rate_hz);
  readDouble(*source, "tf_check_wait_s", 0.0, false, 60.0, p.tf_check_wait_s);
  readInt(*source, "overlay_max_points", 100, 10000000, p.overlay_max_points);
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
          {"progress_log_period_s", formatDouble(p.progress_log_period_s)},
          {"status_rate_hz", formatDouble(p.status_rate_hz)},
          {"tf_check_wait_s", formatDouble(p.tf_check_wait_s)},
          {"overlay_max_points", std::to_string(p.overlay_max_points)}};
}

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
