#include "thermal_lidar_calibration/core/timing_check.hpp"

#include "thermal_lidar_calibration/core/loss.hpp"
#include "thermal_lidar_calibration/core/person_timing.hpp"
#include "thermal_lidar_calibration/core/timed_refinement.hpp"
#include "thermal_lidar_calibration/core/timing_resolution.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace thermal_lidar_calibration {
namespace {

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
  t.asked = result.time_offset_asked;
  t.time_offset_s = result.time_offset_s;
  if (uncertainty && uncertainty->timed && uncertainty->resamples >= 2) t.halfwidth_ms = uncertainty->time_offset_ms;
  std::vector<std::size_t> used;
  for (std::size_t i = 0; i < pairs.size() && i < result.inliers.size(); ++i) {
    if (result.inliers[i]) used.push_back(i);
  }
  const TimingResolution r =
      timingResolution(camera, pairs, used, result.extrinsic, result.time_offset_s);
  if (r.pairs_with_motion == 0) return std::nullopt;
  t.pairs_with_motion = r.pairs_with_motion;
  t.resolution_ms = r.resolution_ms;
  t.mean_image_speed_px_s = std::accumulate(r.image_speed_px_s.begin(), r.image_speed_px_s.end(), 0.0) /
                            static_cast<double>(r.image_speed_px_s.size());
  std::vector<double> losses;
  for (std::size_t i : r.pairs) losses.push_back(i < result.pair_losses.size() ? result.pair_losses[i] : 0.0);
  t.speed_loss_correlation = rankCorrelation(r.image_speed_px_s, losses);
  if (t.mode != TimeOffsetMode::kEstimate) probeOffset(camera, pairs, result, timing, behind_camera_penalty_c1, t);
  return t;
}

}  // namespace thermal_lidar_calibration
