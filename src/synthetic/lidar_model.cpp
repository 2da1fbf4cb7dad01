#include "thermal_lidar_calibration/synthetic/lidar_model.hpp"

#include <cmath>
#include <stdexcept>

namespace thermal_lidar_calibration {
namespace synthetic {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

std::vector<double> evenlySpacedRad(double first_deg, double last_deg, int count) {
  std::vector<double> out(count);
  for (int i = 0; i < count; ++i) {
    out[i] = (first_deg + (last_deg - first_deg) * i / (count - 1)) * kDegToRad;
  }
  return out;
}

}  // namespace

double LidarModel::azimuthRad(int azimuth_index) const {
  return 2.0 * M_PI * azimuth_index / azimuth_count;
}

Eigen::Vector3d LidarModel::direction(int beam, int azimuth_index) const {
  const double el = elevations_rad.at(beam);
  const double az = azimuthRad(azimuth_index);
  return Eigen::Vector3d(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
}

void LidarModel::validate() const {
  if (elevations_rad.empty()) throw std::invalid_argument("LiDAR model '" + name + "' has no beams");
  if (azimuth_count < 4) throw std::invalid_argument("LiDAR model '" + name + "': azimuth_count must be >= 4");
  if (!(min_range_m > 0.0 && max_range_m > min_range_m)) {
    throw std::invalid_argument("LiDAR model '" + name + "': need 0 < min_range_m < max_range_m");
  }
}

LidarModel LidarModel::hdl32e() {
  LidarModel m;
  m.name = "HDL-32E";
  m.elevations_rad = evenlySpacedRad(-30.67, 10.67, 32);
  m.azimuth_count = 2170;
  m.min_range_m = 1.0;
  m.max_range_m = 100.0;
  return m;
}

LidarModel LidarModel::vlp16() {
  LidarModel m;
  m.name = "VLP-16";
  m.elevations_rad = evenlySpacedRad(-15.0, 15.0, 16);
  m.azimuth_count = 1800;
  m.min_range_m = 1.0;
  m.max_range_m = 100.0;
  return m;
}

}  // namespace synthetic
}  // namespace thermal_lidar_calibration
