#pragma once
// Where parameter values come from: a read-only view of flat "key: value" parameters. The YAML
// source below reads a --config file (the format of config/default.yaml); ros/ adds one over a
// node's private NodeHandle. The parameter tables (app/parameters/parameter_table.hpp) read through it.

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace thermal_lidar_calibration {

class ParameterSource {
 public:
  virtual ~ParameterSource() = default;
  virtual bool has(const std::string& key) const = 0;
  // An integer is accepted as a double; a double is never accepted as an integer.
  virtual std::optional<double> getDouble(const std::string& key) const = 0;
  virtual std::optional<long long> getInt(const std::string& key) const = 0;  // rejects 1.5
  virtual std::optional<std::string> getString(const std::string& key) const = 0;
  virtual std::optional<bool> getBool(const std::string& key) const = 0;
};

// Throws std::invalid_argument on a bad file (missing, not YAML, not a map). An empty file is
// an empty map: every key keeps its default.
std::unique_ptr<ParameterSource> makeYamlParameterSource(const std::string& path);

// Top-level keys of a YAML parameter file, in file order (for the unknown-key warning).
// Throws std::invalid_argument on a bad file.
std::vector<std::string> yamlFileKeys(const std::string& path);

}  // namespace thermal_lidar_calibration
