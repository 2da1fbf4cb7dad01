#include "thermal_lidar_calibration/detection/scan_view_top.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace thermal_lidar_calibration {
namespace detection {
namespace {

// Range bins of 1 m from 2 m (nearer: the vehicle itself) to 60 m.
constexpr float kNearM = 2.0f;
constexpr int kBins = 58;
// A bin is on the line when its highest point is within this of it; no bin may be higher.
constexpr float kOnLineM = 0.05f;
// The line must hold the highest points of this many bins, spread over this many metres: a
// wall or a tree line rising above the top beam gives dozens; chance alignments of person and
// post tops do not.
constexpr int kMinBinsOnLine = 6;
constexpr float kMinSpreadM = 5.0f;
// Real top beams look up (HDL-64E +2 deg, HDL-32E +10.7, VLP-16 and most others +15) from an
// origin within a few decimetres of the sensor's: a flat line (the tops of a hedge along the line
// of sight) is not the view's top.
const double kMinSlope = std::tan(1.0 * M_PI / 180.0);
const double kMaxSlope = std::tan(60.0 * M_PI / 180.0);
constexpr double kMaxOffsetM = 0.5;

}  // namespace

void ScanViewTop::fit(const std::vector<Eigen::Vector3f>& points, const std::vector<float>& heights,
                      float min_height_m) {
  found_ = false;
  constexpr float kNone = -std::numeric_limits<float>::infinity();
  bin_top_z_.assign(kBins, kNone);
  bin_top_r_.assign(kBins, 0.f);
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!(heights[i] > min_height_m)) continue;  // ground, or unknown (NaN)
    const Eigen::Vector3f& p = points[i];
    const float r2 = p.x() * p.x() + p.y() * p.y();
    if (!(r2 >= kNearM * kNearM)) continue;  // also NaN
    const float r = std::sqrt(r2);
    const int b = static_cast<int>(r - kNearM);
    if (b >= kBins || !(p.z() > bin_top_z_[b])) continue;
    bin_top_z_[b] = p.z();
    bin_top_r_[b] = r;
  }
  std::vector<int> used;
  for (int b = 0; b < kBins; ++b) {
    if (bin_top_z_[b] > kNone && std::isfinite(bin_top_z_[b])) used.push_back(b);
  }
  // Lines through pairs of bin tops (the upper hull's edges are among them); the one that bounds
  // every bin and holds the most wins, the first on ties (deterministic).
  int best_count = 0;
  for (std::size_t i = 0; i < used.size(); ++i) {
    for (std::size_t j = i + 1; j < used.size(); ++j) {
      const float r0 = bin_top_r_[used[i]], z0 = bin_top_z_[used[i]];
      const float r1 = bin_top_r_[used[j]], z1 = bin_top_z_[used[j]];
      if (r1 - r0 < kMinSpreadM) continue;
      const double slope = (z1 - z0) / (r1 - r0);
      const double offset = z0 - slope * r0;
      if (slope < kMinSlope || slope > kMaxSlope || std::fabs(offset) > kMaxOffsetM) continue;
      int count = 0;
      float lo = std::numeric_limits<float>::infinity(), hi = -lo;
      bool bounds = true;
      for (int b : used) {
        const double above = bin_top_z_[b] - (offset + slope * bin_top_r_[b]);
        if (above > kOnLineM) {
          bounds = false;
          break;
        }
        if (above >= -kOnLineM) {
          ++count;
          lo = std::min(lo, bin_top_r_[b]);
          hi = std::max(hi, bin_top_r_[b]);
        }
      }
      if (!bounds || count < kMinBinsOnLine || hi - lo < kMinSpreadM || count <= best_count) continue;
      best_count = count;
      found_ = true;
      offset_m_ = offset;
      slope_ = slope;
    }
  }
}

double ScanViewTop::elevationDeg() const { return std::atan(slope_) * 180.0 / M_PI; }

double ScanViewTop::gapBelowDeg(const std::vector<Eigen::Vector3f>& points, const std::vector<int>& indices) const {
  if (!found_) return std::numeric_limits<double>::infinity();
  double gap = std::numeric_limits<double>::infinity();
  for (int i : indices) {
    const Eigen::Vector3f& p = points[i];
    const double r = std::hypot(p.x(), p.y());
    if (r < kNearM) continue;
    const double below = std::atan2(offset_m_ + slope_ * r, r) - std::atan2(p.z(), r);
    gap = std::min(gap, below);
  }
  return gap * 180.0 / M_PI;
}

}  // namespace detection
}  // namespace thermal_lidar_calibration
