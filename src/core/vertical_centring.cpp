#include "thermal_lidar_calibration/core/vertical_centring.hpp"

#include <Eigen/Geometry>

#include "region_centre.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

namespace thermal_lidar_calibration {
namespace {

using region::bestPoint;
using region::Directions;
using region::directionsFor;
using region::Point;
using region::regionCentre;
using region::traceOutline;

// A resample's refined pose lies within a pixel or so of the estimate's: its search starts smaller.
constexpr double kResampleFirstStep = 0.25;
// consensusPoint's slope: this times the mean loss with the margin (px) is added to the count of
// pairs that leave it. The count alone is flat between one pair's edge and the next, where the
// compass search would stop; any slope well below one pair does (0.001 to 0.1 gave the same
// results on the ideal-topic drives).
constexpr double kConsensusSlope = 0.01;
constexpr double kAbsoluteTolerance = 1e-5;
constexpr int kMaxFitRounds = 6;
constexpr int kBisections = 10;  // boundary to 1/1024 of its bracket

// Pose at coordinates q (pixels): a rotation about the camera's x axis through the pivot by
// q[0] / fy and the translation q[1] * depth / fy along its y axis (pixels at the pivot's
// depth), then, in three dimensions, a turn of the camera about its own optical axis (the
// image's roll) by q[2] pixels at the image's side edge.
class CentringSpace {
 public:
  CentringSpace(const Extrinsic& origin, const Eigen::Vector3d& pivot_lidar, const CameraModel& camera)
      : R_(origin.rotationMatrix()), t_(origin.translation) {
    pivot_ = R_ * pivot_lidar + t_;
    rad_per_px_ = 1.0 / camera.fy;
    m_per_px_ = pivot_.z() / camera.fy;
    roll_rad_per_px_ = 2.0 / camera.width;
  }
  double pivotDepth() const { return pivot_.z(); }
  template <int N>
  Extrinsic at(const Eigen::Matrix<double, N, 1>& q) const {
    const Eigen::Matrix3d D =
        Eigen::AngleAxisd(q[0] * rad_per_px_, Eigen::Vector3d::UnitX()).toRotationMatrix();
    Extrinsic e = Extrinsic::fromRotationMatrix(D * R_, D * (t_ - pivot_) + pivot_);
    e.translation.y() += q[1] * m_per_px_;
    if constexpr (N == 3) {
      const Eigen::Matrix3d roll =
          Eigen::AngleAxisd(q[2] * roll_rad_per_px_, Eigen::Vector3d::UnitZ()).toRotationMatrix();
      e = Extrinsic::fromRotationMatrix(roll * e.rotationMatrix(), roll * e.translation);
    }
    return e;
  }

 private:
  Eigen::Matrix3d R_;
  Eigen::Vector3d t_, pivot_;
  double rad_per_px_ = 0.0, m_per_px_ = 0.0, roll_rad_per_px_ = 0.0;
};

// The margin's reading at points of the space: Eq. (3) over `pairs`, or, given `outside_px`, how
// many of them (duplicates counted) cost more than that (the region of config.outlying_fraction).
template <int N>
class SpaceLoss {
 public:
  SpaceLoss(const LossEvaluator& loss, const CentringSpace& space, const std::vector<std::size_t>& pairs,
            int threads, std::uint64_t& evaluations, std::optional<double> outside_px = std::nullopt)
      : loss_(loss), space_(space), pairs_(pairs), threads_(threads), evaluations_(evaluations),
        outside_px_(outside_px) {}
  std::vector<double> operator()(const std::vector<Point<N>>& qs) const {
    std::vector<Extrinsic> candidates;
    candidates.reserve(qs.size());
    for (const Point<N>& q : qs) candidates.push_back(space_.at<N>(q));
    std::vector<double> out;
    if (outside_px_) {
      loss_.pairsAboveBatch(candidates, pairs_, *outside_px_, out, threads_);
    } else {
      loss_.lossBatch(candidates, pairs_, out, threads_);
    }
    evaluations_ += qs.size();
    return out;
  }

 private:
  const LossEvaluator& loss_;
  const CentringSpace& space_;
  const std::vector<std::size_t>& pairs_;
  int threads_;
  std::uint64_t& evaluations_;
  std::optional<double> outside_px_;
};

// What the region reads: with outlying_fraction, how many pairs cost more than pair_fit_px (a
// pair that fits); without, the loss.
std::optional<double> regionCount(const VerticalCentringConfig& config) {
  return config.outlying_fraction > 0.0 ? std::optional<double>(config.pair_fit_px) : std::nullopt;
}

// The region's level in pairs: at most this many may leave the margin (half a pair above the
// whole number, so that the count's comparison does not hang on rounding).
double outlyingLevel(double fraction, std::size_t pairs) {
  return std::floor(fraction * static_cast<double>(pairs)) + 0.5;
}

// The region's level over `fitting` pairs, in what regionCount says the region reads: the pairs
// that may leave the margin, or the loss level `loss_level`.
double regionLevel(const VerticalCentringConfig& config, std::size_t fitting, double loss_level) {
  return regionCount(config) ? outlyingLevel(config.outlying_fraction, fitting) : loss_level;
}

std::vector<std::size_t> keepOnly(const std::vector<std::size_t>& pairs, const std::vector<std::size_t>& allowed) {
  std::vector<std::size_t> out;
  for (const std::size_t i : pairs) {
    if (std::binary_search(allowed.begin(), allowed.end(), i)) out.push_back(i);
  }
  return out;
}

// The margin's reading alone: the stretch of poses that fit is the masks', not the ring ends'
// (those pull toward one pose; the calibration centres without them, so must a resample).
LossEvaluator marginReading(const LossEvaluator& loss, const VerticalCentringConfig& config) {
  return loss.withPixelRule(PixelRule::kBilinear).withMargin(config.margin_px).withoutRingEnds();
}

// The estimate's move as a point of the space (the resamples start there), and back.
template <int N>
Point<N> shiftOf(const VerticalCentringOutcome& o) {
  Point<N> q;
  q[0] = o.shift_rotation_px;
  q[1] = o.shift_translation_px;
  if constexpr (N == 3) q[2] = o.shift_roll_px;
  return q;
}

template <int N>
void applyCentre(const CentringSpace& space, const Point<N>& centre, VerticalCentringOutcome& out) {
  out.extrinsic = space.at<N>(centre);
  out.applied = true;
  out.skipped_because.clear();
  out.shift_rotation_px = centre[0];
  out.shift_translation_px = centre[1];
  if constexpr (N == 3) out.shift_roll_px = centre[2];
}

// The pose, from q, at which the fewest of `pairs` leave the margin (a compass search on their
// count, with kConsensusSlope's slope): where the pairs that fit are chosen (consensus_start).
template <int N>
Point<N> consensusPoint(const LossEvaluator& with_margin, const CentringSpace& space,
                        const std::vector<std::size_t>& pairs, double pair_fit_px, int threads,
                        std::uint64_t& evaluations, const Point<N>& q) {
  const SpaceLoss<N> loss(with_margin, space, pairs, threads, evaluations);
  const SpaceLoss<N> count(with_margin, space, pairs, threads, evaluations, pair_fit_px);
  const auto f = [&](const std::vector<Point<N>>& qs) {
    std::vector<double> out = count(qs);
    const std::vector<double> mean = loss(qs);
    for (std::size_t k = 0; k < out.size(); ++k) out[k] += kConsensusSlope * mean[k];
    return out;
  };
  double value = 0.0;
  return bestPoint(f, q, value);
}

// centreVertically's work past the checks, in the plane (N = 2) or with the roll (N = 3).
template <int N>
void centreEstimate(const LossEvaluator& with_margin, const CentringSpace& space,
                    const std::vector<std::size_t>& pairs, const VerticalCentringConfig& config, int threads,
                    VerticalCentringOutcome& out) {
  // The pairs that fit within the margin at the space's best pose; the others (a mask eroded by
  // the segmentation, a person half missed) are left out and the best pose sought again. The
  // first best pose is where the most pairs fit (consensus_start), not the loss's minimum, which
  // the pairs that fit nowhere pull their way.
  std::vector<std::size_t> fitting = pairs;
  Point<N> centre = Point<N>::Zero();
  double best = 0.0;
  for (int round = 0; round < kMaxFitRounds; ++round) {
    const SpaceLoss<N> g(with_margin, space, fitting, threads, out.evaluations);
    if (round == 0 && config.consensus_start && config.pair_fit_px > 0.0) {
      centre = consensusPoint<N>(with_margin, space, fitting, config.pair_fit_px, threads, out.evaluations, centre);
      best = g({centre})[0];
    } else {
      centre = bestPoint(g, centre, best);
    }
    if (config.pair_fit_px <= 0.0) break;
    const Extrinsic at_best = space.at<N>(centre);
    std::vector<std::size_t> kept;
    for (const std::size_t i : fitting) {
      if (with_margin.pairLoss(i, at_best) <= config.pair_fit_px) kept.push_back(i);
    }
    out.evaluations += 1;
    if (kept.size() == fitting.size()) break;
    fitting = std::move(kept);
    if (static_cast<double>(fitting.size()) < config.min_fitting_fraction * static_cast<double>(pairs.size())) {
      break;
    }
  }
  out.fitting_pairs = fitting.size();
  out.fitting = fitting;
  std::sort(out.fitting.begin(), out.fitting.end());
  out.fitting.erase(std::unique(out.fitting.begin(), out.fitting.end()), out.fitting.end());
  out.best_cost_px = best;
  if (static_cast<double>(fitting.size()) < config.min_fitting_fraction * static_cast<double>(pairs.size())) {
    out.skipped_because = "too few pairs fit within the margin";
    return;
  }
  if (best > config.max_mean_cost_px) {
    out.skipped_because = "points do not fit within the margin";
    return;
  }
  const SpaceLoss<N> f(with_margin, space, fitting, threads, out.evaluations, regionCount(config));
  out.level_px = best * (1.0 + config.tolerance) + kAbsoluteTolerance;
  const double level = regionLevel(config, fitting.size(), out.level_px);
  if (!regionCentre(f, centre, level, directionsFor<N>(config.rays), config.iterations, kBisections)) {
    out.skipped_because = "region unbounded";
    return;
  }
  // The outline around the centre in the resamples' directions: where their traces start.
  if (!traceOutline(f, centre, directionsFor<N>(config.resample_rays).rays, level, config.resample_bisections,
                    out.resample_reach_px)) {
    out.skipped_because = "region unbounded";
    return;
  }
  applyCentre(space, centre, out);
}

// centreResample's work past the checks.
template <int N>
void centreResampleIn(const LossEvaluator& with_margin, const CentringSpace& space,
                      const std::vector<std::size_t>& fitting, const VerticalCentringOutcome& estimate, int threads,
                      VerticalCentringOutcome& out) {
  const VerticalCentringConfig& config = estimate.config;
  const SpaceLoss<N> f(with_margin, space, fitting, threads, out.evaluations);
  // Where the estimate's centring moved the estimate; if the resample's points do not fit there,
  // its best pose is sought as for the estimate.
  Point<N> centre = shiftOf<N>(estimate);
  double here = f({centre})[0];
  if (here > estimate.level_px) {
    centre = bestPoint(f, centre, here, kResampleFirstStep, estimate.level_px);
  }
  out.best_cost_px = here;
  out.level_px = std::max(estimate.level_px, here * (1.0 + config.tolerance) + kAbsoluteTolerance);
  // Counting, as many pairs may leave the margin as the estimate's share allows, or as already do here.
  const SpaceLoss<N> region(with_margin, space, fitting, threads, out.evaluations, regionCount(config));
  double level = regionLevel(config, fitting.size(), out.level_px);
  if (regionCount(config)) level = std::max(level, region({centre})[0] + 0.5);
  if (!regionCentre(region, centre, level, directionsFor<N>(config.resample_rays), 1, config.resample_bisections,
                    &estimate.resample_reach_px)) {
    out.skipped_because = "region unbounded";
    return;
  }
  applyCentre(space, centre, out);
  out.fitting_pairs = fitting.size();
}

}  // namespace

VerticalCentringOutcome centreVertically(const LossEvaluator& loss, const Extrinsic& start,
                                         const std::vector<std::size_t>& pairs,
                                         const VerticalCentringConfig& config, int threads) {
  config.validate();
  VerticalCentringOutcome out;
  out.config = config;
  out.extrinsic = start;
  if (!config.enabled) return out;
  out.ran = true;
  const LossEvaluator with_margin = marginReading(loss, config);
  const CentringSpace space(start, with_margin.centroid(pairs), with_margin.camera());
  if (!(space.pivotDepth() > 0.0)) {
    out.skipped_because = "pivot behind the camera";
    return out;
  }
  if (config.centre_roll) {
    centreEstimate<3>(with_margin, space, pairs, config, threads, out);
  } else {
    centreEstimate<2>(with_margin, space, pairs, config, threads, out);
  }
  return out;
}

VerticalCentringOutcome centreResample(const LossEvaluator& loss, const Extrinsic& start,
                                       const std::vector<std::size_t>& resample,
                                       const VerticalCentringOutcome& estimate, int threads) {
  VerticalCentringOutcome out;
  out.config = estimate.config;
  out.extrinsic = start;
  out.ran = estimate.ran;
  if (!estimate.applied) {
    out.skipped_because = estimate.skipped_because;
    return out;
  }
  const VerticalCentringConfig& config = estimate.config;
  const LossEvaluator with_margin = marginReading(loss, config);
  const std::vector<std::size_t> fitting =
      config.pair_fit_px > 0.0 ? keepOnly(resample, estimate.fitting) : resample;
  if (fitting.empty()) {
    out.skipped_because = "no resampled pair fits within the margin";
    return out;
  }
  const CentringSpace space(start, with_margin.centroid(fitting), with_margin.camera());
  if (!(space.pivotDepth() > 0.0)) {
    out.skipped_because = "pivot behind the camera";
    return out;
  }
  if (config.centre_roll) {
    centreResampleIn<3>(with_margin, space, fitting, estimate, threads, out);
  } else {
    centreResampleIn<2>(with_margin, space, fitting, estimate, threads, out);
  }
  return out;
}

}  // namespace thermal_lidar_calibration
