#include "thermal_lidar_calibration/core/timing_resolution.hpp"

#include "thermal_lidar_calibration/core/person_timing.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace thermal_lidar_calibration {
namespace {

// A pixel: the Eq. 3 loss of a fit says little about how far a point may move unnoticed (inside a
// mask the distance is zero; a fit that is still off says more about the fit than the data),
// while mask edges and the rings' spacing blur people by about this much.
constexpr double kResidualPx = 1.0;
// Points per pair in the linearisation: plenty for a 7x7 matrix, cheap on big clusters.
constexpr std::size_t kPointsPerPair = 64;

}  // namespace

TimingResolution timingResolution(const CameraModel& camera, const std::vector<CalibrationPair>& pairs,
                                  const std::vector<std::size_t>& used, const Extrinsic& extrinsic,
                                  double time_offset_s) {
  TimingResolution out;
  const Eigen::Matrix3d R = extrinsic.rotationMatrix();
  const Eigen::Vector3d& tr = extrinsic.translation;
  Eigen::Matrix<double, 7, 7> H = Eigen::Matrix<double, 7, 7>::Zero();
  double noise_information = 0.0;  // what the velocities' errors alone add to H(6, 6), expected
  for (std::size_t i : used) {
    if (i >= pairs.size() || !hasMeasuredMotion(pairs[i])) continue;
    const CalibrationPair& pair = pairs[i];
    std::map<std::int32_t, Eigen::Vector3d> variance;  // of each measured person's velocity
    for (const PersonMotion& m : pair.motion) {
      const Eigen::Vector3d se = deskewVelocityStdError(m);
      if (m.measured() && se.allFinite()) variance[m.label] = se.cwiseProduct(se);
    }
    const std::vector<Eigen::Vector3f> at = pointsAtImageTime(pair, time_offset_s);
    const std::size_t stride = std::max<std::size_t>(1, at.size() / kPointsPerPair);
    Eigen::Matrix<double, 7, 7> Hp = Eigen::Matrix<double, 7, 7>::Zero();
    double speed = 0.0, noise = 0.0;
    std::size_t n = 0;
    for (std::size_t k = 0; k < at.size(); k += stride) {
      const Eigen::Vector3d pc = R * at[k].cast<double>() + tr;
      if (pc.z() <= 0.1) continue;
      Eigen::Matrix<double, 2, 3> J;  // pinhole: d(u, v) / d(camera point)
      J << camera.fx / pc.z(), 0.0, -camera.fx * pc.x() / (pc.z() * pc.z()), 0.0, camera.fy / pc.z(),
          -camera.fy * pc.y() / (pc.z() * pc.z());
      Eigen::Matrix3d turn;  // a small turn w moves pc by w x pc = -[pc]x w
      turn << 0, pc.z(), -pc.y(), -pc.z(), 0, pc.x(), pc.y(), -pc.x(), 0;
      Eigen::Matrix<double, 2, 7> A;
      A.leftCols<3>() = J * turn;
      A.block<2, 3>(0, 3) = J;
      A.col(6) = J * (R * pair.point_velocity[k].cast<double>());
      Hp += A.transpose() * A;
      speed += A.col(6).norm();
      const auto var = k < pair.labels.size() ? variance.find(pair.labels[k]) : variance.end();
      if (var != variance.end()) {
        const Eigen::Matrix<double, 2, 3> JR = J * R;
        noise += (JR * var->second.asDiagonal() * JR.transpose()).trace();
      }
      ++n;
    }
    if (n == 0) continue;
    H += Hp / static_cast<double>(n);
    noise_information += noise / static_cast<double>(n);
    out.pairs.push_back(i);
    out.image_speed_px_s.push_back(speed / static_cast<double>(n));
  }
  out.pairs_with_motion = out.pairs.size();
  if (out.pairs.empty()) {
    out.resolution_ms = std::numeric_limits<double>::infinity();
    return out;
  }
  // delta's information with the pose free: the Schur complement of the pose block.
  const Eigen::Matrix<double, 6, 6> Hpp = H.topLeftCorner<6, 6>();
  const Eigen::Matrix<double, 6, 1> Hpd = H.block<6, 1>(0, 6);
  // Less what the velocities' own errors put there: they move each person's points differently,
  // which no pose mimics, so they would otherwise read as resolution (on a steady drive past
  // standing people, whose true motion every pose change mimics, that is all there is).
  const double information = H(6, 6) - Hpd.dot(Eigen::LDLT<Eigen::Matrix<double, 6, 6>>(Hpp).solve(Hpd)) -
                             noise_information;
  out.resolution_ms = information > 0.0 ? 1000.0 * kResidualPx / std::sqrt(information)
                                        : std::numeric_limits<double>::infinity();
  return out;
}

}  // namespace thermal_lidar_calibration
