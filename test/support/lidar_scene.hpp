#pragma once
// Crafted LiDAR scans for the person detector's tests and benchmark: the synthetic rig's
// HDL-32E / VLP-16 beam model and its body, post and bush solids, ray cast over a height-field
// terrain (flat, sloped or rolling) from a mount that may be tilted, with range noise from a
// fixed seed. Each point carries its ring and the id of the person it hit (0 = ground or clutter).

#include "thermal_lidar_calibration/synthetic/body_model.hpp"
#include "thermal_lidar_calibration/synthetic/lidar_model.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cmath>
#include <cstdint>
#include <functional>
#include <random>
#include <vector>

namespace thermal_lidar_calibration {
namespace test_support {

// Ground height z = height(x, y) in the world frame (z up); max_slope bounds |grad height|.
struct Terrain {
  std::function<double(double, double)> height = [](double, double) { return 0.0; };
  double max_slope = 0.0;

  static Terrain flat() { return {}; }
  static Terrain sloped(double slope_x, double slope_y) {
    return {[=](double x, double y) { return slope_x * x + slope_y * y; }, std::hypot(slope_x, slope_y)};
  }
  // Gentle field undulations: two crossing waves of `amplitude_m` and wavelengths 25 m / 37 m
  // (slopes up to ~2 * pi * amplitude / wavelength each).
  static Terrain rolling(double amplitude_m) {
    const double k1 = 2 * M_PI / 25.0, k2 = 2 * M_PI / 37.0;
    return {[=](double x, double y) {
              return amplitude_m * (std::sin(k1 * x + 0.3) * std::cos(k1 * 0.7 * y) + 0.8 * std::sin(k2 * (x + y)));
            },
            amplitude_m * (k1 * 1.3 + 0.8 * k2 * 1.42)};
  }
};

struct Mount {
  double height_m = 1.9;  // sensor above the ground under it
  double roll_deg = 0.0;  // about the sensor's x (forward)
  double pitch_deg = 0.0; // about y (left); positive tips the front down
  Eigen::Isometry3d worldFromSensor(const Terrain& terrain) const {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(0, 0, terrain.height(0, 0) + height_m);
    T.linear() = (Eigen::AngleAxisd(pitch_deg * M_PI / 180, Eigen::Vector3d::UnitY()) *
                  Eigen::AngleAxisd(roll_deg * M_PI / 180, Eigen::Vector3d::UnitX()))
                     .toRotationMatrix();
    return T;
  }
};

struct SceneObject {
  synthetic::Solid solid;  // world frame, standing on the terrain
  int person_id = 0;       // > 0 for a person
};

// Solids placed on the terrain at (x, y).
inline SceneObject personAt(const Terrain& terrain, double x, double y, int id, double height_m = 1.75,
                            double heading_rad = 0.0, double swing_rad = 0.0, double gait_phase_rad = 0.0) {
  synthetic::BodyPose pose;
  pose.ground_xy = Eigen::Vector2d(x, y);
  pose.height_m = height_m;
  pose.heading_rad = heading_rad;
  pose.swing_rad = swing_rad;
  pose.gait_phase_rad = gait_phase_rad;
  Eigen::Isometry3d lift = Eigen::Isometry3d::Identity();
  lift.translation().z() = terrain.height(x, y);
  return {synthetic::makePersonBody(pose).transformed(lift), id};
}
inline SceneObject postAt(const Terrain& terrain, double x, double y, double height_m, double radius_m) {
  Eigen::Isometry3d lift = Eigen::Isometry3d::Identity();
  lift.translation().z() = terrain.height(x, y);
  return {synthetic::makePost(Eigen::Vector2d(x, y), height_m, radius_m).transformed(lift), 0};
}
inline SceneObject bushAt(const Terrain& terrain, double x, double y, const Eigen::Vector3d& radii_m) {
  Eigen::Isometry3d lift = Eigen::Isometry3d::Identity();
  lift.translation().z() = terrain.height(x, y);
  return {synthetic::makeBush(Eigen::Vector2d(x, y), radii_m).transformed(lift), 0};
}
// An ellipsoid resting on the terrain (a vehicle body, a wall segment, a tree crown on a trunk).
inline SceneObject blobAt(const Terrain& terrain, double x, double y, double z_centre_above_ground,
                          const Eigen::Vector3d& radii_m, double yaw_rad = 0.0) {
  synthetic::Solid solid;
  solid.add(synthetic::Ellipsoid{Eigen::Vector3d(x, y, terrain.height(x, y) + z_centre_above_ground),
                                 Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix(), radii_m});
  return {solid, 0};
}

// A KITTI-like Velodyne HDL-64E (its nominal beam layout): 32 beams from -24.33 to -8.83 deg
// (0.5 deg apart) and 32 from -8.33 to +2 deg (0.333 deg apart), 2083 azimuths (0.173 deg). Its
// top beam looks only 2 deg up: from a 1.73 m mount nothing above 2.25 m is seen at 15 m.
inline synthetic::LidarModel hdl64eLike() {
  synthetic::LidarModel m;
  m.name = "HDL-64E-like";
  for (int b = 0; b < 32; ++b) m.elevations_rad.push_back((-24.33 + 0.5 * b) * M_PI / 180.0);
  for (int b = 0; b < 32; ++b) m.elevations_rad.push_back((-8.33 + 10.33 * b / 31.0) * M_PI / 180.0);
  m.azimuth_count = 2083;
  return m;
}

struct CraftedScan {
  std::vector<Eigen::Vector3f> points;  // sensor frame
  std::vector<std::uint16_t> ring;
  std::vector<int> person_id;           // 0 = not a person
  int pointsOf(int id) const {
    int n = 0;
    for (int p : person_id) n += p == id;
    return n;
  }
};

// One instantaneous scan; every `azimuth_step`-th azimuth; returns within [1, max_range_m].
inline CraftedScan castScan(const synthetic::LidarModel& lidar, const Terrain& terrain, const Mount& mount,
                            const std::vector<SceneObject>& objects, double range_noise_m = 0.0,
                            std::uint64_t seed = 1, int azimuth_step = 1, double max_range_m = 100.0) {
  const Eigen::Isometry3d T = mount.worldFromSensor(terrain);
  const Eigen::Vector3d origin = T.translation();
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uniform(1e-12, 1.0);
  auto gaussian = [&]() {  // Box-Muller: the same numbers with every standard library
    return std::sqrt(-2.0 * std::log(uniform(rng))) * std::cos(2 * M_PI * uniform(rng));
  };
  CraftedScan scan;
  for (int b = 0; b < lidar.beamCount(); ++b) {
    for (int a = 0; a < lidar.azimuth_count; a += azimuth_step) {
      synthetic::Ray ray;
      ray.origin = origin;
      ray.direction = T.linear() * lidar.direction(b, a);
      double best = max_range_m;
      int hit_id = -1;
      for (const SceneObject& object : objects) {
        double t = 0.0;
        if (object.solid.intersect(ray, best, &t)) {
          best = t;
          hit_id = object.person_id;
        }
      }
      // Terrain: march while above it, in steps the slope bound makes safe, then bisect.
      double t = 0.0;
      const double lipschitz = 1.0 + terrain.max_slope;
      while (t < best) {
        const Eigen::Vector3d p = origin + t * ray.direction;
        const double gap = p.z() - terrain.height(p.x(), p.y());
        if (gap < 1e-3) {
          hit_id = 0;
          best = t;
          break;
        }
        if (ray.direction.z() > 0 && p.z() > origin.z() + 50) break;
        t += std::max(gap / lipschitz, 1e-3);
      }
      if (hit_id < 0 || best < 1.0) continue;
      const double range = best + (range_noise_m > 0 ? range_noise_m * gaussian() : 0.0);
      scan.points.push_back((lidar.direction(b, a) * range).cast<float>());
      scan.ring.push_back(static_cast<std::uint16_t>(b));
      scan.person_id.push_back(hit_id);
    }
  }
  return scan;
}

}  // namespace test_support
}  // namespace thermal_lidar_calibration
