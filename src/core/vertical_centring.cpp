#include "thermal_lidar_calibration/core/vertical_centring.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace thermal_lidar_calibration {
namespace {

// The region is traced out to at most kFirstStep * 2^kMaxDoublings pixels from its centre; a
// direction still inside there counts as unbounded.
constexpr double kFirstStep = 0.25;
constexpr int kMaxDoublings = 12;
constexpr double kMinSearchStep = 1e-3;  // pixels: the plane's best pose to this step
// A resample's refined pose lies within a pixel or so of the estimate's: its search starts smaller.
constexpr double kResampleFirstStep = 0.25;
constexpr double kAbsoluteTolerance = 1e-5;
constexpr int kMaxFitRounds = 6;
constexpr int kBisections = 10;  // boundary to 1/1024 of its bracket

// Pose at plane coordinates q (pixels at the pivot's depth): rotation about the camera's x
// axis through the pivot by q[0] / fy, then the translation q[1] * depth / fy along its y axis.
class VerticalPlane {
 public:
  VerticalPlane(const Extrinsic& origin, const Eigen::Vector3d& pivot_lidar, double fy)
      : R_(origin.rotationMatrix()), t_(origin.translation) {
    pivot_ = R_ * pivot_lidar + t_;
    rad_per_px_ = 1.0 / fy;
    m_per_px_ = pivot_.z() / fy;
  }
  double pivotDepth() const { return pivot_.z(); }
  Extrinsic at(const Eigen::Vector2d& q) const {
    const Eigen::Matrix3d D =
        Eigen::AngleAxisd(q.x() * rad_per_px_, Eigen::Vector3d::UnitX()).toRotationMatrix();
    Extrinsic e = Extrinsic::fromRotationMatrix(D * R_, D * (t_ - pivot_) + pivot_);
    e.translation.y() += q.y() * m_per_px_;
    return e;
  }

 private:
  Eigen::Matrix3d R_;
  Eigen::Vector3d t_, pivot_;
  double rad_per_px_ = 0.0, m_per_px_ = 0.0;
};

class PlaneLoss {
 public:
  PlaneLoss(const LossEvaluator& loss, const VerticalPlane& plane,
            const std::vector<std::size_t>& pairs, int threads, std::uint64_t& evaluations)
      : loss_(loss), plane_(plane), pairs_(pairs), threads_(threads), evaluations_(evaluations) {}
  std::vector<double> operator()(const std::vector<Eigen::Vector2d>& qs) const {
    std::vector<Extrinsic> candidates;
    candidates.reserve(qs.size());
    for (const Eigen::Vector2d& q : qs) candidates.push_back(plane_.at(q));
    std::vector<double> out;
    loss_.lossBatch(candidates, pairs_, out, threads_);
    evaluations_ += qs.size();
    return out;
  }

 private:
  const LossEvaluator& loss_;
  const VerticalPlane& plane_;
  const std::vector<std::size_t>& pairs_;
  int threads_;
  std::uint64_t& evaluations_;
};

// Compass search in the plane from q: the four +-step probes in one batch, halving the step
// when none improves; it stops early once the loss is at most `good_enough`.
Eigen::Vector2d bestInPlane(const PlaneLoss& f, Eigen::Vector2d q, double& fq, double first_step = 1.0,
                            double good_enough = -1.0) {
  fq = f({q})[0];
  for (double step = first_step; step >= kMinSearchStep && !(fq <= good_enough);) {
    const std::vector<Eigen::Vector2d> probes{q + Eigen::Vector2d(step, 0), q - Eigen::Vector2d(step, 0),
                                              q + Eigen::Vector2d(0, step), q - Eigen::Vector2d(0, step)};
    const std::vector<double> values = f(probes);
    int best = -1;
    for (int k = 0; k < 4; ++k) {
      if (values[k] < fq) {
        fq = values[k];
        best = k;
      }
    }
    if (best < 0) {
      step *= 0.5;
    } else {
      q = probes[best];
    }
  }
  return q;
}

// Distance from `centre` to the region's edge along each direction (all directions bracketed,
// then bisected, together); false if some direction is still inside at the largest distance.
// `first` (optional, one per direction) is where each bracket's first probe goes.
bool traceOutline(const PlaneLoss& f, const Eigen::Vector2d& centre,
                  const std::vector<Eigen::Vector2d>& directions, double level, int bisections,
                  std::vector<double>& reach, const std::vector<double>* first = nullptr) {
  const std::size_t n = directions.size();
  std::vector<double> inside(n, 0.0), outside(n, kFirstStep);
  if (first) {
    for (std::size_t k = 0; k < n; ++k) outside[k] = std::max((*first)[k], kFirstStep);
  }
  std::vector<bool> bracketed(n, false);
  for (int round = 0; round <= kMaxDoublings; ++round) {
    std::vector<Eigen::Vector2d> probes;
    std::vector<std::size_t> which;
    for (std::size_t k = 0; k < n; ++k) {
      if (bracketed[k]) continue;
      probes.push_back(centre + outside[k] * directions[k]);
      which.push_back(k);
    }
    if (probes.empty()) break;
    const std::vector<double> values = f(probes);
    for (std::size_t j = 0; j < which.size(); ++j) {
      const std::size_t k = which[j];
      if (values[j] > level) {
        bracketed[k] = true;
      } else if (round < kMaxDoublings) {
        inside[k] = outside[k];
        outside[k] *= 2.0;
      }
    }
  }
  for (std::size_t k = 0; k < n; ++k) {
    if (!bracketed[k]) return false;
  }
  for (int b = 0; b < bisections; ++b) {
    std::vector<Eigen::Vector2d> probes(n);
    for (std::size_t k = 0; k < n; ++k) {
      probes[k] = centre + 0.5 * (inside[k] + outside[k]) * directions[k];
    }
    const std::vector<double> values = f(probes);
    for (std::size_t k = 0; k < n; ++k) {
      (values[k] <= level ? inside[k] : outside[k]) = 0.5 * (inside[k] + outside[k]);
    }
  }
  reach = inside;
  return true;
}

// Centroid of the polygon through the points centre + reach[k] * directions[k] (in angle order).
Eigen::Vector2d polygonCentroid(const Eigen::Vector2d& centre,
                                const std::vector<Eigen::Vector2d>& directions,
                                const std::vector<double>& reach) {
  double twice_area = 0.0;
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  const std::size_t n = directions.size();
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::Vector2d p = reach[k] * directions[k];
    const Eigen::Vector2d q = reach[(k + 1) % n] * directions[(k + 1) % n];
    const double cross = p.x() * q.y() - q.x() * p.y();
    twice_area += cross;
    sum += (p + q) * cross;
  }
  if (!(twice_area > 0.0)) return centre;  // degenerate (a point or a line): stay
  return centre + sum / (3.0 * twice_area);
}

std::vector<Eigen::Vector2d> rayDirections(int rays) {
  std::vector<Eigen::Vector2d> directions;
  for (int k = 0; k < rays; ++k) {
    const double angle = 2.0 * M_PI * k / rays;
    directions.emplace_back(std::cos(angle), std::sin(angle));
  }
  return directions;
}

// The region's centroid, traced from `centre` `iterations` times; false if it is unbounded.
bool regionCentre(const PlaneLoss& f, Eigen::Vector2d& centre, double level, int rays, int iterations,
                  int bisections, const std::vector<double>* first = nullptr) {
  const std::vector<Eigen::Vector2d> directions = rayDirections(rays);
  std::vector<double> reach;
  for (int i = 0; i < iterations; ++i) {
    if (!traceOutline(f, centre, directions, level, bisections, reach, i == 0 ? first : nullptr)) return false;
    // A region that is not convex may have its centroid outside: then keep the last centre.
    const Eigen::Vector2d next = polygonCentroid(centre, directions, reach);
    if (f({next})[0] > level) break;
    centre = next;
  }
  return true;
}

std::vector<std::size_t> keepOnly(const std::vector<std::size_t>& pairs, const std::vector<std::size_t>& allowed) {
  std::vector<std::size_t> out;
  for (const std::size_t i : pairs) {
    if (std::binary_search(allowed.begin(), allowed.end(), i)) out.push_back(i);
  }
  return out;
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
  // The margin's reading alone: the stretch of poses that fit is the masks', not the ring ends'
  // (those pull toward one pose; the calibration centres without them, so must a resample).
  const LossEvaluator with_margin =
      loss.withPixelRule(PixelRule::kBilinear).withMargin(config.margin_px).withoutRingEnds();
  const VerticalPlane plane(start, with_margin.centroid(pairs), with_margin.camera().fy);
  if (!(plane.pivotDepth() > 0.0)) {
    out.skipped_because = "pivot behind the camera";
    return out;
  }
  // The pairs that fit within the margin at the plane's best pose; the others (a mask eroded by
  // the segmentation, a person half missed) are left out and the best pose sought again.
  std::vector<std::size_t> fitting = pairs;
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  double best = 0.0;
  for (int round = 0; round < kMaxFitRounds; ++round) {
    const PlaneLoss g(with_margin, plane, fitting, threads, out.evaluations);
    centre = bestInPlane(g, centre, best);
    if (config.pair_fit_px <= 0.0) break;
    const Extrinsic at_best = plane.at(centre);
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
    return out;
  }
  if (best > config.max_mean_cost_px) {
    out.skipped_because = "points do not fit within the margin";
    return out;
  }
  const PlaneLoss f(with_margin, plane, fitting, threads, out.evaluations);
  out.level_px = best * (1.0 + config.tolerance) + kAbsoluteTolerance;
  if (!regionCentre(f, centre, out.level_px, config.rays, config.iterations, kBisections)) {
    out.skipped_because = "region unbounded";
    return out;
  }
  // The outline around the centre in the resamples' directions: where their traces start.
  if (!traceOutline(f, centre, rayDirections(config.resample_rays), out.level_px, config.resample_bisections,
                    out.resample_reach_px)) {
    out.skipped_because = "region unbounded";
    return out;
  }
  out.extrinsic = plane.at(centre);
  out.applied = true;
  out.skipped_because.clear();
  out.shift_rotation_px = centre.x();
  out.shift_translation_px = centre.y();
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
  const LossEvaluator with_margin =
      loss.withPixelRule(PixelRule::kBilinear).withMargin(config.margin_px).withoutRingEnds();
  const std::vector<std::size_t> fitting =
      config.pair_fit_px > 0.0 ? keepOnly(resample, estimate.fitting) : resample;
  if (fitting.empty()) {
    out.skipped_because = "no resampled pair fits within the margin";
    return out;
  }
  const VerticalPlane plane(start, with_margin.centroid(fitting), with_margin.camera().fy);
  if (!(plane.pivotDepth() > 0.0)) {
    out.skipped_because = "pivot behind the camera";
    return out;
  }
  const PlaneLoss f(with_margin, plane, fitting, threads, out.evaluations);
  // Where the estimate's centring moved the estimate; if the resample's points do not fit there,
  // its best pose is sought as for the estimate.
  Eigen::Vector2d centre(estimate.shift_rotation_px, estimate.shift_translation_px);
  double here = f({centre})[0];
  if (here > estimate.level_px) {
    centre = bestInPlane(f, centre, here, kResampleFirstStep, estimate.level_px);
  }
  out.best_cost_px = here;
  out.level_px = std::max(estimate.level_px, here * (1.0 + config.tolerance) + kAbsoluteTolerance);
  if (!regionCentre(f, centre, out.level_px, config.resample_rays, 1, config.resample_bisections,
                    &estimate.resample_reach_px)) {
    out.skipped_because = "region unbounded";
    return out;
  }
  out.extrinsic = plane.at(centre);
  out.applied = true;
  out.skipped_because.clear();
  out.fitting_pairs = fitting.size();
  out.shift_rotation_px = centre.x();
  out.shift_translation_px = centre.y();
  return out;
}

}  // namespace thermal_lidar_calibration
