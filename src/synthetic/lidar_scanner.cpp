#include "thermal_lidar_calibration/synthetic/lidar_scanner.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace thermal_lidar_calibration {
namespace synthetic {

ScanGrid::ScanGrid(const LidarModel& lidar, double ground_z)
    : lidar_(lidar),
      range_(static_cast<std::size_t>(lidar.beamCount()) * lidar.azimuth_count,
             std::numeric_limits<double>::infinity()),
      owner_(range_.size(), -2) {
  const int azimuths = lidar.azimuth_count;
  for (const double el : lidar.elevations_rad) {
    cos_el_.push_back(std::cos(el));
    sin_el_.push_back(std::sin(el));
  }
  for (int a = 0; a < azimuths; ++a) {
    const double az = lidar.azimuthRad(a);
    cos_az_.push_back(std::cos(az));
    sin_az_.push_back(std::sin(az));
  }
  // Ground: a downward beam meets the plane at the same range for every azimuth.
  for (int b = 0; b < lidar.beamCount(); ++b) {
    const double el = lidar.elevations_rad[b];
    if (el < 0.0) {
      Ray down;
      down.direction = direction(b, 0);
      double t = 0.0;
      if (intersectHorizontalPlane(ground_z, down, &t) && t <= lidar.max_range_m &&
          t >= lidar.min_range_m) {
        for (int a = 0; a < azimuths; ++a) {
          range_[b * azimuths + a] = t;
          owner_[b * azimuths + a] = -1;
        }
      }
    }
  }
}

void ScanGrid::cast(const Solid& solid, int object, const std::vector<int>* sector_of, int sector) {
  const int beams = lidar_.beamCount();
  const int azimuths = lidar_.azimuth_count;
  const double az_step = 2.0 * M_PI / azimuths;
  const Eigen::Vector3d& c = solid.boundingCentre();
  const double r = solid.boundingRadius();
  const double dist = c.norm();
  if (dist - r > lidar_.max_range_m) return;
  const double horiz = c.head<2>().norm();
  int a_begin = 0, a_end = azimuths - 1;
  double el_lo = -M_PI_2, el_hi = M_PI_2;
  if (horiz > r && dist > r) {
    const double az_c = std::atan2(c.y(), c.x());
    const double half = std::asin(r / horiz);
    a_begin = static_cast<int>(std::floor((az_c - half) / az_step));
    a_end = static_cast<int>(std::ceil((az_c + half) / az_step));
    const double el_c = std::atan2(c.z(), horiz);
    const double el_half = std::asin(r / dist);
    el_lo = el_c - el_half;
    el_hi = el_c + el_half;
  }
  Ray ray;
  for (int b = 0; b < beams; ++b) {
    const double el = lidar_.elevations_rad[b];
    if (el < el_lo || el > el_hi) continue;
    for (int ai = a_begin; ai <= a_end; ++ai) {
      const int a = ((ai % azimuths) + azimuths) % azimuths;
      if (sector_of && (*sector_of)[static_cast<std::size_t>(a)] != sector) continue;
      ray.direction = direction(b, a);
      const std::size_t k = static_cast<std::size_t>(b) * azimuths + a;
      double t = 0.0;
      if (solid.intersect(ray, std::min(range_[k], lidar_.max_range_m), &t) && t >= lidar_.min_range_m) {
        range_[k] = t;
        owner_[k] = object;
      }
    }
  }
}

std::vector<LidarReturn> ScanGrid::returns() const {
  const int azimuths = lidar_.azimuth_count;
  std::vector<LidarReturn> out;
  out.reserve(range_.size() / 2);
  for (int b = 0; b < lidar_.beamCount(); ++b) {
    for (int a = 0; a < azimuths; ++a) {
      const std::size_t k = static_cast<std::size_t>(b) * azimuths + a;
      if (owner_[k] == -2) continue;
      LidarReturn ret;
      ret.point = (direction(b, a) * range_[k]).cast<float>();
      ret.range_m = static_cast<float>(range_[k]);
      ret.object = owner_[k];
      ret.beam = b;
      ret.azimuth = a;
      out.push_back(ret);
    }
  }
  return out;
}

std::vector<LidarReturn> castLidarScan(const LidarModel& lidar, const std::vector<WorldObject>& objects,
                                       double ground_z) {
  ScanGrid grid(lidar, ground_z);
  for (std::size_t j = 0; j < objects.size(); ++j) grid.cast(objects[j].solid, static_cast<int>(j));
  return grid.returns();
}

}  // namespace synthetic
}  // namespace thermal_lidar_calibration
