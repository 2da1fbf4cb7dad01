#include "thermal_lidar_calibration/synthetic/lidar_scanner.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace thermal_lidar_calibration {
namespace synthetic {

std::vector<LidarReturn> castLidarScan(const LidarModel& lidar, const std::vector<WorldObject>& objects,
                                       double ground_z) {
  const int beams = lidar.beamCount();
  const int azimuths = lidar.azimuth_count;
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> range(static_cast<std::size_t>(beams) * azimuths, inf);
  std::vector<int> owner(range.size(), -2);  // -2 none, -1 ground, >= 0 object

  // Ground: a downward beam meets the plane at the same range for every azimuth.
  for (int b = 0; b < beams; ++b) {
    const double el = lidar.elevations_rad[b];
    if (el < 0.0) {
      Ray down;
      down.direction = lidar.direction(b, 0);
      double t = 0.0;
      if (intersectHorizontalPlane(ground_z, down, &t) && t <= lidar.max_range_m &&
          t >= lidar.min_range_m) {
        for (int a = 0; a < azimuths; ++a) {
          range[b * azimuths + a] = t;
          owner[b * azimuths + a] = -1;
        }
      }
    }
  }

  const double az_step = 2.0 * M_PI / azimuths;
  Ray ray;
  for (std::size_t j = 0; j < objects.size(); ++j) {
    const Solid& solid = objects[j].solid;
    const Eigen::Vector3d& c = solid.boundingCentre();
    const double r = solid.boundingRadius();
    const double dist = c.norm();
    if (dist - r > lidar.max_range_m) continue;
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
    for (int b = 0; b < beams; ++b) {
      const double el = lidar.elevations_rad[b];
      if (el < el_lo || el > el_hi) continue;
      const double ce = std::cos(el), se = std::sin(el);
      for (int ai = a_begin; ai <= a_end; ++ai) {
        const int a = ((ai % azimuths) + azimuths) % azimuths;
        const double az = lidar.azimuthRad(a);
        ray.direction = Eigen::Vector3d(ce * std::cos(az), ce * std::sin(az), se);
        const std::size_t k = static_cast<std::size_t>(b) * azimuths + a;
        double t = 0.0;
        if (solid.intersect(ray, std::min(range[k], lidar.max_range_m), &t) && t >= lidar.min_range_m) {
          range[k] = t;
          owner[k] = static_cast<int>(j);
        }
      }
    }
  }

  std::vector<LidarReturn> returns;
  returns.reserve(range.size() / 2);
  for (int b = 0; b < beams; ++b) {
    for (int a = 0; a < azimuths; ++a) {
      const std::size_t k = static_cast<std::size_t>(b) * azimuths + a;
      if (owner[k] == -2) continue;
      LidarReturn ret;
      ret.point = (lidar.direction(b, a) * range[k]).cast<float>();
      ret.range_m = static_cast<float>(range[k]);
      ret.object = owner[k];
      ret.beam = b;
      ret.azimuth = a;
      returns.push_back(ret);
    }
  }
  return returns;
}

}  // namespace synthetic
}  // namespace thermal_lidar_calibration
