#include "thermal_lidar_calibration/core/stored_pair_spacing.hpp"

#include <algorithm>
#include <cmath>

namespace thermal_lidar_calibration {

StoredPairSpacing::StoredPairSpacing(std::vector<StoredPairStamp> pairs, int skip_frames) {
  for (const StoredPairStamp& p : pairs) stamps_.push_back(p.stamp_s);
  std::sort(stamps_.begin(), stamps_.end());
  if (skip_frames <= 0) return;
  std::vector<StoredPairStamp> numbered;
  for (const StoredPairStamp& p : pairs) {
    if (p.frame_index) numbered.push_back(p);
  }
  if (numbered.size() < 2 || numbered.size() != pairs.size()) return;
  std::sort(numbered.begin(), numbered.end(),
            [](const StoredPairStamp& a, const StoredPairStamp& b) { return *a.frame_index < *b.frame_index; });
  std::vector<double> periods;
  for (std::size_t k = 1; k < numbered.size(); ++k) {
    const double frames = static_cast<double>(*numbered[k].frame_index - *numbered[k - 1].frame_index);
    const double seconds = numbered[k].stamp_s - numbered[k - 1].stamp_s;
    if (frames > 0.0 && seconds > 0.0) periods.push_back(seconds / frames);
  }
  if (periods.empty()) return;
  std::nth_element(periods.begin(), periods.begin() + static_cast<std::ptrdiff_t>(periods.size() / 2), periods.end());
  period_s_ = periods[periods.size() / 2];
  // Half a frame beyond the last frame the rule passes over: stamps jitter.
  window_s_ = (static_cast<double>(skip_frames) + 0.5) * *period_s_;
}

bool StoredPairSpacing::tooClose(double stamp_s) const {
  if (!period_s_) return false;
  const auto at = std::lower_bound(stamps_.begin(), stamps_.end(), stamp_s - window_s_);
  for (auto it = at; it != stamps_.end() && *it <= stamp_s + window_s_; ++it) {
    if (std::abs(*it - stamp_s) > 1e-9) return true;
  }
  return false;
}

}  // namespace thermal_lidar_calibration
