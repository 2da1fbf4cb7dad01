#include "thermal_lidar_calibration/app/parameters/point_time_field.hpp"

#include <algorithm>
#include <cctype>
#include <stdexcept>

namespace thermal_lidar_calibration {

PointTimeField PointTimeField::parse(const std::string& value) {
  PointTimeField out;
  if (value == "auto") return out;
  if (value == "none") {
    out.mode = Mode::kNone;
    return out;
  }
  const bool name_like = !value.empty() && std::all_of(value.begin(), value.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_';
  });
  if (!name_like) {
    throw std::invalid_argument("must be auto, none or the name of a PointCloud2 field (letters, digits, _)");
  }
  out.mode = Mode::kNamed;
  out.name = value;
  return out;
}

const std::vector<std::string>& PointTimeField::autoNames() {
  static const std::vector<std::string> names = {"time", "t", "timestamp", "offset_time"};
  return names;
}

}  // namespace thermal_lidar_calibration
