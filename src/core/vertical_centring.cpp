#include "thermal_lidar_calibration/core/vertical_centring.hpp"

#include <Eigen/Geometry>

#include <cmath>

namespace thermal_lidar_calibration {
namespace {

// The region is traced out to at most kFirstStep * 2^kMaxDoublings pixels from its centre; a
// direction still inside there counts as unbounded.
constexpr double kFirstStep = 0.25;
constexpr int kMaxDoublings = 12;
constexpr int kBisections = 10;        // boundary to 1/1024 of its bracket
constexpr double kMinSearchStep = 1e-3;  // pixels: the plane's best pose to this step
constexpr double kAbsoluteTolerance = 1e-5;

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
// when none improves.
Eigen::Vector2d bestInPlane(const PlaneLoss& f, Eigen::Vector2d q, double& fq) {
  fq = f({q})[0];
  for (double step = 1.0; step >= kMinSearchStep;) {
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
bool traceOutline(const PlaneLoss& f, const Eigen::Vector2d& centre,
                  const std::vector<Eigen::Vector2d>& directions, double level,
                  std::vector<double>& reach) {
  const std::size_t n = directions.size();
  std::vector<double> inside(n, 0.0), outside(n, kFirstStep);
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
  for (int b = 0; b < kBisections; ++b) {
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
  const LossEvaluator with_margin =
      loss.withPixelRule(PixelRule::kBilinear).withMargin(config.margin_px);
  const VerticalPlane plane(start, with_margin.centroid(pairs), with_margin.camera().fy);
  if (!(plane.pivotDepth() > 0.0)) {
    out.skipped_because = "pivot behind the camera";
    return out;
  }
  const PlaneLoss f(with_margin, plane, pairs, threads, out.evaluations);
  double best = 0.0;
  Eigen::Vector2d centre = bestInPlane(f, Eigen::Vector2d::Zero(), best);
  out.best_cost_px = best;
  if (best > config.max_mean_cost_px) {
    out.skipped_because = "points do not fit within the margin";
    return out;
  }
  const double level = best * (1.0 + config.tolerance) + kAbsoluteTolerance;
  std::vector<Eigen::Vector2d> directions;
  for (int k = 0; k < config.rays; ++k) {
    const double angle = 2.0 * M_PI * k / config.rays;
    directions.emplace_back(std::cos(angle), std::sin(angle));
  }
  std::vector<double> reach;
  for (int i = 0; i < config.iterations; ++i) {
    if (!traceOutline(f, centre, directions, level, reach)) {
      out.skipped_because = "region unbounded";
      return out;
    }
    // A region that is not convex may have its centroid outside: then keep the last centre.
    const Eigen::Vector2d next = polygonCentroid(centre, directions, reach);
    if (f({next})[0] > level) break;
    centre = next;
  }
  out.extrinsic = plane.at(centre);
  out.applied = true;
  out.skipped_because.clear();
  out.shift_rotation_px = centre.x();
  out.shift_translation_px = centre.y();
  return out;
}

}  // namespace thermal_lidar_calibration
