#pragma once
// Synthetic pairs whose camera is late or early (issue 21): each person of a pair gets a
// velocity relative to the LiDAR, and its LiDAR points are moved to where that person was
// `delay_s` before the image's instant (the mask shows the world at stamp + delay_s, the points
// were captured at the stamp). Velocities vary from pair to pair unless `steady` (a straight
// drive at one speed past standing people: then the delay cannot be told from a translation).

#include "thermal_lidar_calibration/core/person_timing.hpp"
#include "thermal_lidar_calibration/core/random.hpp"

#include "synthetic_pairs.hpp"

#include <map>

namespace thermal_lidar_calibration {
namespace test_support {

struct MotionOptions {
  double delay_s = 0.06;        // the true time offset delta
  bool steady = false;          // every person moves at (-speed, 0, 0): undetectable delay
  double speed_mps = 2.0;       // the vehicle's speed (its mean, when not steady)
  double speed_spread_mps = 1.5;  // +- around it, per pair (stops and starts)
  double walk_mps = 1.2;        // a person's own walk, any direction, up to this
  double yaw_rate_rad_s = 0.15; // turning, up to this: people move sideways by omega * range
  std::uint64_t seed = 21;
};

inline void addMotion(std::vector<CalibrationPair>& pairs, const MotionOptions& o) {
  Rng rng(o.seed);
  for (CalibrationPair& pair : pairs) {
    const double speed = o.steady ? o.speed_mps : o.speed_mps + rng.uniform(-o.speed_spread_mps, o.speed_spread_mps);
    const double yaw_rate = o.steady ? 0.0 : rng.uniform(-o.yaw_rate_rad_s, o.yaw_rate_rad_s);
    std::map<std::int32_t, Eigen::Vector3d> velocity;
    std::map<std::int32_t, Eigen::Vector3d> centre;
    std::map<std::int32_t, int> count;
    for (std::size_t i = 0; i < pair.points.size(); ++i) {
      // Eigen leaves a default-constructed vector uninitialised: start each sum at zero.
      auto it = centre.try_emplace(pair.labels[i], Eigen::Vector3d::Zero()).first;
      it->second += pair.points[i].cast<double>();
      ++count[pair.labels[i]];
    }
    std::vector<PersonMotion> motion;
    for (auto& [label, c] : centre) {
      c /= count[label];
      // A point fixed in the world seen from a vehicle moving at `speed` along x and turning at
      // yaw_rate: v = -speed e_x - omega x p.
      Eigen::Vector3d v(-speed + yaw_rate * c.y(), -yaw_rate * c.x(), 0.0);
      if (!o.steady) {
        const double heading = rng.uniform(-M_PI, M_PI), walk = rng.uniform(0.0, o.walk_mps);
        v += Eigen::Vector3d(walk * std::cos(heading), walk * std::sin(heading), 0.0);
      }
      velocity[label] = v;
      PersonMotion m;
      m.label = label;
      m.velocity_mps = v;
      m.scans = 5;
      motion.push_back(m);
    }
    // The mask shows each person at stamp + delay; the points were captured at the stamp.
    for (std::size_t i = 0; i < pair.points.size(); ++i) {
      pair.points[i] = (pair.points[i].cast<double>() - velocity[pair.labels[i]] * o.delay_s).cast<float>();
    }
    pair.cloud_stamp_s = pair.stamp_s;
    attachMotion(pair, motion);
  }
}

// The pairs with their points moved to the image's instant at `delta` and no motion left.
inline std::vector<CalibrationPair> pairsAtOffset(const std::vector<CalibrationPair>& pairs, double delta) {
  std::vector<CalibrationPair> out = pairsAtImageTime(pairs, delta);
  for (CalibrationPair& p : out) p.point_velocity.clear();
  return out;
}

}  // namespace test_support
}  // namespace thermal_lidar_calibration
