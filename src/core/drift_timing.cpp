#include "thermal_lidar_calibration/core/drift_timing.hpp"

#include "thermal_lidar_calibration/core/loss.hpp"
#include "thermal_lidar_calibration/core/person_timing.hpp"

#include <cmath>

namespace thermal_lidar_calibration {

CalibrationPair rebasedAtTimeOffset(CalibrationPair pair, double time_offset_s) {
  if (!hasMeasuredMotion(pair)) return pair;
  pair.points = pointsAtImageTime(pair, time_offset_s);
  pair.cloud_stamp_s = pair.stamp_s;
  pair.point_time_s.clear();
  return pair;
}

std::optional<TimingChangeFit> fitTimingChange(const CameraModel& camera, const std::vector<CalibrationPair>& window,
                                               const Extrinsic& reference, const Extrinsic& fit_pose,
                                               double max_change_s, double behind_camera_penalty_c1,
                                               double threshold_px) {
  TimingChangeFit fit;
  for (const CalibrationPair& p : window) fit.pairs_with_motion += hasMeasuredMotion(p) ? 1 : 0;
  if (fit.pairs_with_motion == 0 || window.empty()) return std::nullopt;
  const LossEvaluator nearest(camera, window, LossConfig{behind_camera_penalty_c1, PixelRule::kNearest, 0.0});
  // The pairs the reference or the window's pose explains, as the held-out test takes them: a
  // mismatched pair costs hundreds of pixels that any shift of its points changes, and would
  // decide the comparison alone.
  std::vector<std::size_t> used;
  for (std::size_t i = 0; i < window.size(); ++i) {
    if (std::min(nearest.pairLoss(i, reference), nearest.pairLoss(i, fit_pose)) <= threshold_px) used.push_back(i);
  }
  if (used.empty()) return std::nullopt;
  fit.pairs_used = used.size();
  const auto lossAt = [&](double d) { return nearest.withTimeOffset(d).loss(reference, used); };
  // A grid, then halving steps around the best: the loss along the offset alone is smooth over
  // a few milliseconds (the points move by their speed times it).
  constexpr double kGridS = 0.005;
  fit.loss = fit.loss_reference = lossAt(0.0);
  fit.loss_fit = nearest.loss(fit_pose, used);
  for (double d = -max_change_s; d <= max_change_s + 1e-12; d += kGridS) {
    const double l = lossAt(d);
    if (l < fit.loss) {
      fit.loss = l;
      fit.change_s = d;
    }
  }
  for (double step = kGridS / 2; step >= 0.0005; step /= 2) {
    for (const double d : {fit.change_s - step, fit.change_s + step}) {
      if (std::abs(d) > max_change_s) continue;
      const double l = lossAt(d);
      if (l < fit.loss) {
        fit.loss = l;
        fit.change_s = d;
      }
    }
  }
  return fit;
}

}  // namespace thermal_lidar_calibration
