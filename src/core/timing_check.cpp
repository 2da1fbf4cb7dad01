#include "thermal_lidar_calibration/core/timing_check.hpp"

#include "thermal_lidar_calibration/core/loss.hpp"
#include "thermal_lidar_calibration/core/person_timing.hpp"
#include "thermal_lidar_calibration/core/timed_refinement.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace thermal_lidar_calibration {
namespace {

// A pixel: below this the Eq. 3 loss of a good fit says little about how far a point may move
// unnoticed (inside a mask the distance is zero), while mask edges and the rings' spacing blur
// people by about this much.
constexpr double kResidualFloorPx = 1.0;
// Points per pair in the linearisation: plenty for a 7x7 matrix, cheap on big clusters.
constexpr std::size_t kPointsPerPair = 64;

std::vector<double> ranks(const std::vector<double>& v) {
  std::vector<std::size_t> order(v.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return v[a] < v[b]; });
  std::vector<double> r(v.size());
  for (std::size_t i = 0; i < order.size();) {
    std::size_t j = i;
    while (j + 1 < order.size() && v[order[j + 1]] == v[order[i]]) ++j;
    const double mean_rank = 0.5 * static_cast<double>(i + j);
    for (std::size_t k = i; k <= j; ++k) r[order[k]] = mean_rank;
    i = j + 1;
  }
  return r;
}

}  // namespace

double rankCorrelation(const std::vector<double>& x, const std::vector<double>& y) {
  if (x.size() != y.size() || x.size() < 3) return 0.0;
  const std::vector<double> rx = ranks(x), ry = ranks(y);
  const double n = static_cast<double>(x.size());
  const double mx = std::accumulate(rx.begin(), rx.end(), 0.0) / n;
  const double my = std::accumulate(ry.begin(), ry.end(), 0.0) / n;
  double sxy = 0.0, sxx = 0.0, syy = 0.0;
  for (std::size_t i = 0; i < rx.size(); ++i) {
    sxy += (rx[i] - mx) * (ry[i] - my);
    sxx += (rx[i] - mx) * (rx[i] - mx);
    syy += (ry[i] - my) * (ry[i] - my);
  }
  return sxx > 0.0 && syy > 0.0 ? sxy / std::sqrt(sxx * syy) : 0.0;
}

namespace {

// Mode none or fixed: where a joint refinement of pose and offset goes from the fit.
void probeOffset(const CameraModel& camera, const std::vector<CalibrationPair>& pairs, const CalibrationResult& result,
                 const TimeOffsetConfig& timing, double c1, TimingAssessment& t) {
  std::vector<std::size_t> used;
  for (std::size_t i = 0; i < result.inliers.size(); ++i) {
    if (result.inliers[i]) used.push_back(i);
  }
  if (used.size() < 3) return;
  const LossEvaluator loss(camera, pairs, LossConfig{c1, PixelRule::kBilinear, result.time_offset_s});
  TimeOffsetConfig probe = timing;
  probe.mode = TimeOffsetMode::kEstimate;
  probe.max_s = std::max(timing.max_s, std::abs(result.time_offset_s));
  RefineConfig refine;  // the default run's search, from the fit
  const TimedRefineOutcome r = TimedRefinement(loss, refine, probe, 0).run(result.extrinsic, result.time_offset_s, used);
  t.fit_loss = loss.loss(result.extrinsic, used);
  t.probe_loss = r.loss;
  t.probe_offset_s = r.time_offset_s;
}

}  // namespace

std::optional<TimingAssessment> assessTiming(const CameraModel& camera, const std::vector<CalibrationPair>& pairs,
                                             const CalibrationResult& result,
                                             const std::optional<Uncertainty>& uncertainty,
                                             const TimeOffsetConfig& timing, double behind_camera_penalty_c1) {
  TimingAssessment t;
  t.mode = result.time_offset_mode;
  t.time_offset_s = result.time_offset_s;
  if (uncertainty && uncertainty->timed && uncertainty->resamples >= 2) t.halfwidth_ms = uncertainty->time_offset_ms;
  const Eigen::Matrix3d R = result.extrinsic.rotationMatrix();
  const Eigen::Vector3d& tr = result.extrinsic.translation;
  // Normal matrix of (rotation, translation, delta) for the points' image positions, each pair
  // weighing one (its points share their errors: one mask, one scan).
  Eigen::Matrix<double, 7, 7> H = Eigen::Matrix<double, 7, 7>::Zero();
  std::vector<double> speeds, losses;
  for (std::size_t i = 0; i < pairs.size() && i < result.inliers.size(); ++i) {
    if (!result.inliers[i] || !hasMeasuredMotion(pairs[i])) continue;
    const CalibrationPair& pair = pairs[i];
    const std::vector<Eigen::Vector3f> at = pointsAtImageTime(pair, result.time_offset_s);
    const std::size_t stride = std::max<std::size_t>(1, at.size() / kPointsPerPair);
    Eigen::Matrix<double, 7, 7> Hp = Eigen::Matrix<double, 7, 7>::Zero();
    double speed = 0.0;
    std::size_t used = 0;
    for (std::size_t k = 0; k < at.size(); k += stride) {
      const Eigen::Vector3d pc = R * at[k].cast<double>() + tr;
      if (pc.z() <= 0.1) continue;
      Eigen::Matrix<double, 2, 3> J;  // pinhole: d(u, v) / d(camera point)
      J << camera.fx / pc.z(), 0.0, -camera.fx * pc.x() / (pc.z() * pc.z()), 0.0, camera.fy / pc.z(),
          -camera.fy * pc.y() / (pc.z() * pc.z());
      Eigen::Matrix3d cross;  // a small turn w moves pc by w x pc = -[pc]x w
      cross << 0, pc.z(), -pc.y(), -pc.z(), 0, pc.x(), pc.y(), -pc.x(), 0;
      Eigen::Matrix<double, 2, 7> A;
      A.leftCols<3>() = J * cross;
      A.block<2, 3>(0, 3) = J;
      A.col(6) = J * (R * pair.point_velocity[k].cast<double>());
      Hp += A.transpose() * A;
      speed += A.col(6).norm();
      ++used;
    }
    if (used == 0) continue;
    H += Hp / static_cast<double>(used);
    speeds.push_back(speed / static_cast<double>(used));
    losses.push_back(i < result.pair_losses.size() ? result.pair_losses[i] : 0.0);
    ++t.pairs_with_motion;
  }
  if (t.pairs_with_motion == 0) return std::nullopt;
  t.mean_image_speed_px_s = std::accumulate(speeds.begin(), speeds.end(), 0.0) / static_cast<double>(speeds.size());
  t.speed_loss_correlation = rankCorrelation(speeds, losses);
  // delta's information with the pose free: the Schur complement of the pose block.
  const Eigen::Matrix<double, 6, 6> Hpp = H.topLeftCorner<6, 6>();
  const Eigen::Matrix<double, 6, 1> Hpd = H.block<6, 1>(0, 6);
  const Eigen::LDLT<Eigen::Matrix<double, 6, 6>> ldlt(Hpp);
  const double information = H(6, 6) - Hpd.dot(ldlt.solve(Hpd));
  const double sigma_px = std::max(result.loss, kResidualFloorPx);
  t.resolution_ms = information > 0.0 ? 1000.0 * sigma_px / std::sqrt(information)
                                      : std::numeric_limits<double>::infinity();
  if (t.mode != TimeOffsetMode::kEstimate) probeOffset(camera, pairs, result, timing, behind_camera_penalty_c1, t);
  return t;
}

}  // namespace thermal_lidar_calibration
