#include "thermal_lidar_calibration/core/person_timing.hpp"

#include <map>
#include <stdexcept>

namespace thermal_lidar_calibration {

Eigen::Vector3d deskewVelocity(const PersonMotion& motion) {
  return Eigen::Vector3d(motion.velocity_mps.x(), motion.velocity_mps.y(), 0.0);
}

Eigen::Vector3d deskewVelocityStdError(const PersonMotion& motion) {
  return Eigen::Vector3d(motion.std_error_mps.x(), motion.std_error_mps.y(), 0.0);
}

bool hasMeasuredMotion(const CalibrationPair& pair) {
  return !pair.point_velocity.empty() && pair.point_velocity.size() == pair.points.size();
}

void attachMotion(CalibrationPair& pair, std::vector<PersonMotion> motion) {
  std::map<std::int32_t, Eigen::Vector3f> by_label;
  pair.turn_rate_rps = 0.0;
  for (const PersonMotion& m : motion) {
    if (!m.measured()) continue;
    by_label[m.label] = deskewVelocity(m).cast<float>();
    pair.turn_rate_rps = m.turn_rate_rps;  // the scan's, the same for every measured person
  }
  pair.point_velocity.assign(pair.points.size(), Eigen::Vector3f::Zero());
  for (std::size_t i = 0; i < pair.points.size() && i < pair.labels.size(); ++i) {
    const auto it = by_label.find(pair.labels[i]);
    if (it != by_label.end()) pair.point_velocity[i] = it->second;
  }
  pair.motion = std::move(motion);
}

double leadTimeS(const CalibrationPair& pair, std::size_t point) {
  const double point_time = point < pair.point_time_s.size() ? pair.point_time_s[point] : 0.0;
  return pair.stamp_s - pair.cloud_stamp_s - point_time;
}

Eigen::Vector3f turnAcceleration(const Eigen::Vector3f& velocity, double turn_rate_rps) {
  const float w = static_cast<float>(turn_rate_rps);
  return Eigen::Vector3f(w * velocity.y(), -w * velocity.x(), 0.0f);
}

std::vector<Eigen::Vector3f> pointsAtImageTime(const CalibrationPair& pair, double time_offset_s) {
  if (!hasMeasuredMotion(pair)) return pair.points;
  std::vector<Eigen::Vector3f> out(pair.points.size());
  for (std::size_t i = 0; i < pair.points.size(); ++i) {
    const double dt = leadTimeS(pair, i) + time_offset_s;
    const Eigen::Vector3d a = turnAcceleration(pair.point_velocity[i], pair.turn_rate_rps).cast<double>();
    out[i] = (pair.points[i].cast<double>() + pair.point_velocity[i].cast<double>() * dt + 0.5 * a * dt * dt)
                 .cast<float>();
  }
  return out;
}

std::vector<CalibrationPair> pairsAtImageTime(const std::vector<CalibrationPair>& pairs,
                                              double time_offset_s) {
  std::vector<CalibrationPair> out = pairs;
  for (CalibrationPair& pair : out) pair.points = pointsAtImageTime(pair, time_offset_s);
  return out;
}

}  // namespace thermal_lidar_calibration
