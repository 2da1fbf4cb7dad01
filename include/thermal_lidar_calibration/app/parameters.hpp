#pragma once
// One table of parameter keys shared by calibration_node (private ~ parameters) and
// calibrate_bag (--config YAML, the same file as config/default.yaml). The loader starts from
// the core defaults, overrides what the source has, validates, and throws
// std::invalid_argument("parameter 'population_size' = -3: must be an integer in [2, 100000]").

#include "thermal_lidar_calibration/core/calibration_config.hpp"
#include "thermal_lidar_calibration/core/frame_gate.hpp"

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace thermal_lidar_calibration {

// Parameters both executables use: optimizer, gating and pairing.
struct CoreParameters {
  CalibrationConfig calibration;
  GateConfig gate;
  double sync_slop_s = 0.05;   // ApproximateTime max interval between image, mask, clusters
  int sync_queue_size = 30;    // ApproximateTime queue per topic
  int pairs_required = 60;     // node: pairs to collect before optimizing
};

// A read-only view of parameters: a YAML map or a ros::NodeHandle.
class ParameterSource {
 public:
  virtual ~ParameterSource() = default;
  virtual bool has(const std::string& key) const = 0;
  virtual std::optional<double> getDouble(const std::string& key) const = 0;
  virtual std::optional<long long> getInt(const std::string& key) const = 0;  // rejects 1.5
  virtual std::optional<std::string> getString(const std::string& key) const = 0;
  virtual std::optional<bool> getBool(const std::string& key) const = 0;
};

// Throws std::invalid_argument on a bad file (missing, not YAML, not a map).
std::unique_ptr<ParameterSource> makeYamlParameterSource(const std::string& path);

CoreParameters loadCoreParameters(const ParameterSource& source);
// Every core key with its effective value, one "key: value" per line (for the start-up log
// and the result file).
std::vector<std::pair<std::string, std::string>> describeCoreParameters(const CoreParameters& p);
// All keys this package knows (core and node-only), to warn about typos in a --config file:
// the keys of describeCoreParameters() then describeNodeParameters(), in their order.
const std::vector<std::string>& knownParameterKeys();

}  // namespace thermal_lidar_calibration
