// camera_calibration / camera_info_manager YAML files <-> CameraModel.

#include "thermal_lidar_calibration/app/files/camera_info_file.hpp"
#include "thermal_lidar_calibration/app/files/camera_calibration.hpp"
#include "thermal_lidar_calibration/app/files/yaml_file.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <stdexcept>

namespace thermal_lidar_calibration {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw std::invalid_argument("camera info file " + path + ": " + what);
}

int readSize(const YAML::Node& root, const std::string& key, const std::string& path) {
  const YAML::Node node = root[key];
  if (!node) fail(path, "missing '" + key + "'; write it as a positive integer (pixels)");
  long long value = 0;
  try {
    value = node.as<long long>();
  } catch (const YAML::Exception&) {
    fail(path, "'" + key + "' is not an integer; write it as a positive integer (pixels)");
  }
  if (value <= 0 || value > 100000) {
    fail(path, "'" + key + "' = " + std::to_string(value) + ": must be an integer in [1, 100000]");
  }
  return static_cast<int>(value);
}

// Reads a {rows, cols, data} matrix (or a plain list) into `expected` values; `allow_empty`
// accepts a missing node or an empty data list (returns an empty vector).
std::vector<double> readMatrix(const YAML::Node& root, const std::string& key,
                               const std::string& path, bool allow_empty) {
  const YAML::Node node = root[key];
  if (!node || node.IsNull()) {
    if (allow_empty) return {};
    fail(path, "missing '" + key + "'; write it as {rows, cols, data: [...]}");
  }
  const YAML::Node data = node.IsMap() ? node["data"] : node;
  if (!data || !data.IsSequence()) {
    if (allow_empty && (!data || data.IsNull())) return {};
    fail(path, "'" + key + "' has no data list; write it as {rows, cols, data: [...]}");
  }
  std::vector<double> values;
  try {
    for (const auto& v : data) values.push_back(v.as<double>());
  } catch (const YAML::Exception&) {
    fail(path, "'" + key + "' data holds a non-number; write numbers only");
  }
  for (double v : values) {
    if (!std::isfinite(v)) fail(path, "'" + key + "' data holds a non-finite number");
  }
  if (node.IsMap() && node["rows"] && node["cols"]) {
    long long rows = 0, cols = 0;
    try {
      rows = node["rows"].as<long long>();
      cols = node["cols"].as<long long>();
    } catch (const YAML::Exception&) {
      fail(path, "'" + key + "' rows/cols are not integers");
    }
    if (rows * cols != static_cast<long long>(values.size())) {
      fail(path, "'" + key + "' says " + std::to_string(rows) + "x" + std::to_string(cols) +
                     " but has " + std::to_string(values.size()) + " values");
    }
  }
  return values;
}

void emitMatrix(YAML::Emitter& out, const std::string& key, int rows, int cols,
                const std::vector<double>& data) {
  out << YAML::Key << key << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "rows" << YAML::Value << rows;
  out << YAML::Key << "cols" << YAML::Value << cols;
  out << YAML::Key << "data" << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (double v : data) out << v;
  out << YAML::EndSeq << YAML::EndMap;
}

}  // namespace

CameraModel loadCameraInfoFile(const std::string& path) {
  const YAML::Node root = loadYamlFile(path, "camera info file");
  if (!root.IsMap()) {
    fail(path, "is not a YAML map; write a camera_calibration file (image_width, image_height, "
               "camera_matrix, distortion_model, distortion_coefficients)");
  }
  const int width = readSize(root, "image_width", path);
  const int height = readSize(root, "image_height", path);
  const std::vector<double> k = readMatrix(root, "camera_matrix", path, false);
  if (k.size() != 9) {
    fail(path, "'camera_matrix' has " + std::to_string(k.size()) + " values, expected 9 (3x3)");
  }
  CameraCalibration calibration;
  calibration.width = width;
  calibration.height = height;
  std::copy(k.begin(), k.end(), calibration.K.begin());
  if (root["distortion_model"] && !root["distortion_model"].IsNull()) {
    calibration.distortion_model = root["distortion_model"].as<std::string>();
  }
  calibration.D = readMatrix(root, "distortion_coefficients", path, true);
  try {
    return cameraModelFromCalibration(calibration);  // the same rules as a CameraInfo message
  } catch (const std::invalid_argument& e) {
    fail(path, e.what());
  }
}

void writeCameraInfoFile(const std::string& path, const CameraModel& camera,
                         const std::string& camera_name) {
  YAML::Emitter out;
  out << YAML::BeginMap;
  out << YAML::Key << "image_width" << YAML::Value << camera.width;
  out << YAML::Key << "image_height" << YAML::Value << camera.height;
  out << YAML::Key << "camera_name" << YAML::Value << camera_name;
  const Eigen::Matrix3d K = camera.K();
  std::vector<double> k;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) k.push_back(K(r, c));
  }
  emitMatrix(out, "camera_matrix", 3, 3, k);
  out << YAML::Key << "distortion_model" << YAML::Value << "plumb_bob";
  emitMatrix(out, "distortion_coefficients", 1, 5,
             std::vector<double>(camera.distortion.begin(), camera.distortion.end()));
  emitMatrix(out, "rectification_matrix", 3, 3, {1, 0, 0, 0, 1, 0, 0, 0, 1});
  emitMatrix(out, "projection_matrix", 3, 4,
             {k[0], k[1], k[2], 0, k[3], k[4], k[5], 0, k[6], k[7], k[8], 0});
  out << YAML::EndMap;
  std::ofstream file(path);
  if (!file) throw std::runtime_error("cannot write camera info file " + path);
  file << out.c_str() << "\n";
  if (!file) throw std::runtime_error("failed writing camera info file " + path);
}

}  // namespace thermal_lidar_calibration
