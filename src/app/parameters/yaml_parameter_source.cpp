// ParameterSource over a YAML map: calibrate_bag --config, the format of config/default.yaml.

#include "thermal_lidar_calibration/app/parameters/parameter_source.hpp"
#include "thermal_lidar_calibration/app/files/yaml_file.hpp"

#include <yaml-cpp/yaml.h>

#include <stdexcept>

namespace thermal_lidar_calibration {
namespace {

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
    const YAML::Node& root = root_;  // const lookup: never inserts the key
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

}  // namespace thermal_lidar_calibration
