#include "thermal_lidar_calibration/core/ring_alias.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace thermal_lidar_calibration {
namespace {

// A ring's points share one elevation to well under this (range noise is along the beam); the
// densest spinning LiDARs space their rings about 0.1 deg apart.
constexpr double kLevelGapRad = 0.05 * M_PI / 180.0;
constexpr int kMinLevelPoints = 3;  // a level needs this many points (a stray point is no ring)
constexpr std::size_t kMaxPoints = 200000;  // enough to see every ring; bounds the sort

constexpr double kMaxWidthOfStep = 0.25;  // a ring's extent at most this share of the spacing

double median(std::vector<double> values) {
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

}  // namespace

RingSpacing ringSpacing(const std::vector<CalibrationPair>& pairs, const std::vector<std::size_t>& used) {
  std::size_t total = 0;
  for (const std::size_t i : used) total += pairs[i].points.size();
  const std::size_t stride = std::max<std::size_t>(1, (total + kMaxPoints - 1) / kMaxPoints);
  std::vector<double> elevations;
  elevations.reserve(std::min(total, kMaxPoints));  // every stride-th point: at most kMaxPoints
  std::size_t k = 0;
  for (const std::size_t i : used) {
    for (const Eigen::Vector3f& p : pairs[i].points) {
      if (k++ % stride != 0) continue;
      const double horizontal = std::hypot(double(p.x()), double(p.y()));
      if (horizontal > 0.0) elevations.push_back(std::atan2(double(p.z()), horizontal));
    }
  }
  std::sort(elevations.begin(), elevations.end());
  std::vector<double> levels, widths;  // mean elevation and extent of each level with enough points
  std::size_t first = 0;
  for (std::size_t j = 1; j <= elevations.size(); ++j) {
    if (j < elevations.size() && elevations[j] - elevations[j - 1] <= kLevelGapRad) continue;
    if (j - first >= static_cast<std::size_t>(kMinLevelPoints)) {
      double sum = 0.0;
      for (std::size_t m = first; m < j; ++m) sum += elevations[m];
      levels.push_back(sum / static_cast<double>(j - first));
      widths.push_back(elevations[j - 1] - elevations[first]);
    }
    first = j;
  }
  RingSpacing out;
  out.levels = static_cast<int>(levels.size());
  if (levels.size() < 3) return out;
  std::vector<double> steps;
  for (std::size_t j = 1; j < levels.size(); ++j) steps.push_back(levels[j] - levels[j - 1]);
  const double step = median(steps);
  // Rings are thin beside their spacing; elevations spread over a continuum (a LiDAR without
  // rings, points from many heights) only break where they happen to thin out, into wide levels.
  if (!(median(widths) <= kMaxWidthOfStep * step)) return out;
  out.spacing_rad = step;
  return out;
}

Extrinsic turnedAboutCameraX(const Extrinsic& e, double angle_rad) {
  const Eigen::Matrix3d D = Eigen::AngleAxisd(angle_rad, Eigen::Vector3d::UnitX()).toRotationMatrix();
  return Extrinsic::fromRotationMatrix(D * e.rotationMatrix(), D * e.translation);
}

bool ringAliasStartWins(double start_loss, double refined_loss) {
  constexpr double kLowerRatio = 0.98;
  constexpr double kMinGainPx = 0.001;  // near-zero losses differ by noise
  return start_loss < kLowerRatio * refined_loss - kMinGainPx;
}

std::vector<RingAliasStart> ringAliasStarts(const Extrinsic& e, double spacing_rad, int turns) {
  std::vector<RingAliasStart> starts;
  if (!(spacing_rad > 0.0)) return starts;
  for (int k = 1; k <= turns; ++k) {
    for (const int turn : {k, -k}) starts.push_back({turn, turnedAboutCameraX(e, turn * spacing_rad)});
  }
  return starts;
}

}  // namespace thermal_lidar_calibration
