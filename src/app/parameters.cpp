// The parameter table shared by calibration_node (~ parameters) and calibrate_bag (--config):
// defaults from the core structs, per-key type and range checks, then the core validate().

#include "thermal_lidar_calibration/app/parameters.hpp"
#include "thermal_lidar_calibration/node/node_parameters.hpp"
#include "thermal_lidar_calibration/app/parameter_readers.hpp"
#include "thermal_lidar_calibration/app/unknown_parameters.hpp"
#include "thermal_lidar_calibration/app/yaml_file.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace thermal_lidar_calibration {
namespace {

// The keys of a describe*Parameters() list, in its order.
std::vector<std::string> keysOf(const std::vector<std::pair<std::string, std::string>>& described) {
  std::vector<std::string> keys;
  keys.reserve(described.size());
  for (const auto& kv : described) keys.push_back(kv.first);
  return keys;
}

// ------------------------------------------------------------------------------------------
// YAML-backed source (the --config file, same format as config/default.yaml).
class YamlParameterSource : public ParameterSource {
 public:
  explicit YamlParameterSource(YAML::Node root) : root_(std::move(root)) {}

  bool has(const std::string& key) const override {
    const YAML::Node n = node(key);
    return n && !n.IsNull();
  }
  std::optional<double> getDouble(const std::string& key) const override {
    return convert<double>(key);
  }
  std::optional<long long> getInt(const std::string& key) const override {
    return convert<long long>(key);
  }
  std::optional<std::string> getString(const std::string& key) const override {
    const YAML::Node n = node(key);
    if (!n || !n.IsScalar()) return std::nullopt;
    return n.Scalar();
  }
  std::optional<bool> getBool(const std::string& key) const override {
    return convert<bool>(key);
  }

 private:
  YAML::Node node(const std::string& key) const {
    const YAML::Node& root = root_;
    return root[key];
  }
  template <typename T>
  std::optional<T> convert(const std::string& key) const {
    const YAML::Node n = node(key);
    if (!n || !n.IsScalar()) return std::nullopt;
    try {
      return n.as<T>();
    } catch (const YAML::Exception&) {
      return std::nullopt;
    }
  }

  YAML::Node root_;
};

YAML::Node loadYamlMap(const std::string& path) {
  const YAML::Node root = loadYamlFile(path, "parameter file");
  if (root.IsNull()) return YAML::Node(YAML::NodeType::Map);  // an empty file: all defaults
  if (!root.IsMap()) {
    throw std::invalid_argument("parameter file " + path +
                                ": is not a YAML map; write one 'key: value' per line");
  }
  return root;
}

}  // namespace

std::unique_ptr<ParameterSource> makeYamlParameterSource(const std::string& path) {
  return std::make_unique<YamlParameterSource>(loadYamlMap(path));
}

std::vector<std::string> yamlFileKeys(const std::string& path) {
  const YAML::Node root = loadYamlMap(path);
  std::vector<std::string> keys;
  for (const auto& kv : root) keys.push_back(kv.first.as<std::string>());
  return keys;
}

std::vector<std::string> unknownParameterKeys(const std::vector<std::string>& keys) {
  const auto& known = knownParameterKeys();
  std::vector<std::string> unknown;
  for (const auto& k : keys) {
    if (std::find(known.begin(), known.end(), k) == known.end()) unknown.push_back(k);
  }
  return unknown;
}

CoreParameters loadCoreParameters(const ParameterSource& source) {
  CoreParameters p;
  CalibrationConfig& c = p.calibration;
  EvolutionConfig& e = c.evolution;
  OutlierConfig& o = c.outlier;
  RefineConfig& r = c.refine;

  int algorithm = static_cast<int>(c.algorithm);
  if (source.has("algorithm")) {
    const auto v = source.getInt("algorithm");
    if (!v || (*v != 1 && *v != 2)) {
      throwBadParameter(source, "algorithm", "must be 1 (plain evolution) or 2 (with outlier rejection)");
    }
    algorithm = static_cast<int>(*v);
  }
  c.algorithm = algorithm == 1 ? Algorithm::kPlain : Algorithm::kOutlierRejection;
  if (source.has("refine")) {
    const auto v = source.getString("refine");
    if (!v || (*v != "none" && *v != "local")) {
      throwBadParameter(source, "refine", "must be 'none' or 'local'");
    }
    r.mode = *v == "none" ? RefineMode::kNone : RefineMode::kLocal;
  }
  readIntParameter(source, "seed", 0, std::numeric_limits<long long>::max(), c.seed);
  readIntParameter(source, "num_threads", 0, 1024, c.num_threads);

  readIntParameter(source, "population_size", 2, 100000, e.population_size);
  readIntParameter(source, "max_iterations", 1, 100000, e.max_iterations);
  readDoubleParameter(source, "rotation_interval_rad", 0.0, true, 10.0, e.rotation_interval_rad);
  readDoubleParameter(source, "translation_interval_m", 0.0, true, 1000.0, e.translation_interval_m);
  readDoubleParameter(source, "elite_fraction", 0.0, false, 1.0, e.elite_fraction);
  readDoubleParameter(source, "crossover_fraction", 0.0, false, 1.0, e.crossover_fraction);
  readIntParameter(source, "initial_population_factor", 1, 1000, e.initial_population_factor);
  readDoubleParameter(source, "sigma_rot_rad", 0.0, true, 3.5, e.sigma_rot_rad);
  readDoubleParameter(source, "sigma_trans_m", 0.0, true, 100.0, e.sigma_trans_m);
  readDoubleParameter(source, "min_inside_fraction", 0.0, false, 1.0, e.min_inside_fraction);
  readDoubleParameter(source, "behind_camera_penalty_c1", 0.0, true, 1e6, c.behind_camera_penalty_c1);

  readIntParameter(source, "min_sample_large", 1, 100000, o.min_sample_large);
  readIntParameter(source, "min_sample_small", 1, 100000, o.min_sample_small);
  readIntParameter(source, "min_sample_switch", 1, 100000, o.min_sample_switch);
  readIntParameter(source, "outlier_iterations", 0, 1000, o.iterations);
  readDoubleParameter(source, "ratio_solution", 0.0, false, 1.0, o.ratio_solution);
  readDoubleParameter(source, "threshold_sample_px", 0.0, true, 1e6, o.threshold_px);

  readDoubleParameter(source, "refine_initial_step_rot_rad", 0.0, true, 1.0, r.initial_step_rot_rad);
  readDoubleParameter(source, "refine_initial_step_trans_m", 0.0, true, 10.0, r.initial_step_trans_m);
  readDoubleParameter(source, "refine_min_step_rot_rad", 0.0, true, 1.0, r.min_step_rot_rad);
  readDoubleParameter(source, "refine_min_step_trans_m", 0.0, true, 10.0, r.min_step_trans_m);
  readIntParameter(source, "refine_max_evaluations", 1, 100000000, r.max_evaluations);
  readBoolParameter(source, "refine_exclude_truncated", r.exclude_truncated);
  readBoolParameter(source, "refine_reselect_inliers", r.reselect_inliers);

  readIntParameter(source, "max_people", 1, 1000, p.gate.max_people);
  readIntParameter(source, "skip_frames", 0, 100000, p.gate.skip_frames);
  readIntParameter(source, "min_points_per_cluster", 1, 1000000, p.gate.min_points_per_cluster);
  readDoubleParameter(source, "sync_slop", 0.0, true, 10.0, p.sync_slop_s);
  readIntParameter(source, "sync_queue_size", 2, 10000, p.sync_queue_size);
  readIntParameter(source, "pairs_required", 1, 100000, p.pairs_required);

  // Cross-key rules (elite + crossover <= 1, min steps below initial steps, ...) are the core's.
  p.calibration.validate();
  p.gate.validate();
  return p;
}

std::vector<std::pair<std::string, std::string>> describeCoreParameters(const CoreParameters& p) {
  const CalibrationConfig& c = p.calibration;
  const EvolutionConfig& e = c.evolution;
  const OutlierConfig& o = c.outlier;
  const RefineConfig& r = c.refine;
  const auto d = formatParameterNumber;
  const auto i = [](long long v) { return std::to_string(v); };
  return {
      {"algorithm", c.algorithm == Algorithm::kPlain ? "1" : "2"},
      {"refine", r.mode == RefineMode::kNone ? "none" : "local"},
      {"seed", std::to_string(c.seed)},
      {"num_threads", i(c.num_threads)},
      {"population_size", i(e.population_size)},
      {"max_iterations", i(e.max_iterations)},
      {"rotation_interval_rad", d(e.rotation_interval_rad)},
      {"translation_interval_m", d(e.translation_interval_m)},
      {"elite_fraction", d(e.elite_fraction)},
      {"crossover_fraction", d(e.crossover_fraction)},
      {"initial_population_factor", i(e.initial_population_factor)},
      {"sigma_rot_rad", d(e.sigma_rot_rad)},
      {"sigma_trans_m", d(e.sigma_trans_m)},
      {"min_inside_fraction", d(e.min_inside_fraction)},
      {"behind_camera_penalty_c1", d(c.behind_camera_penalty_c1)},
      {"min_sample_large", i(o.min_sample_large)},
      {"min_sample_small", i(o.min_sample_small)},
      {"min_sample_switch", i(o.min_sample_switch)},
      {"outlier_iterations", i(o.iterations)},
      {"ratio_solution", d(o.ratio_solution)},
      {"threshold_sample_px", d(o.threshold_px)},
      {"refine_initial_step_rot_rad", d(r.initial_step_rot_rad)},
      {"refine_initial_step_trans_m", d(r.initial_step_trans_m)},
      {"refine_min_step_rot_rad", d(r.min_step_rot_rad)},
      {"refine_min_step_trans_m", d(r.min_step_trans_m)},
      {"refine_max_evaluations", i(r.max_evaluations)},
      {"refine_exclude_truncated", r.exclude_truncated ? "true" : "false"},
      {"refine_reselect_inliers", r.reselect_inliers ? "true" : "false"},
      {"max_people", i(p.gate.max_people)},
      {"skip_frames", i(p.gate.skip_frames)},
      {"min_points_per_cluster", i(p.gate.min_points_per_cluster)},
      {"sync_slop", d(p.sync_slop_s)},
      {"sync_queue_size", i(p.sync_queue_size)},
      {"pairs_required", i(p.pairs_required)},
  };
}

const std::vector<std::string>& knownParameterKeys() {
  // The describe functions list every key once, core keys first, in the order of the tables.
  static const std::vector<std::string> keys = [] {
    std::vector<std::string> k = keysOf(describeCoreParameters(CoreParameters{}));
    const std::vector<std::string> node_keys = keysOf(ros_io::describeNodeParameters(ros_io::NodeParameters{}));
    k.insert(k.end(), node_keys.begin(), node_keys.end());
    return k;
  }();
  return keys;
}

}  // namespace thermal_lidar_calibration
