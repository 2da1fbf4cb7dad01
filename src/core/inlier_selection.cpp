#include "thermal_lidar_calibration/core/inlier_selection.hpp"

#include <algorithm>
#include <utility>

namespace thermal_lidar_calibration {

std::vector<std::size_t> refinementCandidates(const LossEvaluator& loss, bool exclude_truncated) {
  const std::size_t n = loss.pairCount();
  std::vector<std::size_t> all, whole;
  for (std::size_t i = 0; i < n; ++i) {
    all.push_back(i);
    if (!loss.maskTouchesImageBorder(i)) whole.push_back(i);
  }
  return exclude_truncated && whole.size() * 2 >= n ? whole : all;
}

std::vector<std::size_t> selectInliers(const LossEvaluator& loss, const Extrinsic& estimate,
                                       double threshold_px,
                                       const std::vector<std::size_t>& candidates) {
  const std::size_t n = candidates.size();
  std::vector<std::pair<double, std::size_t>> scored;
  for (std::size_t i : candidates) scored.emplace_back(loss.pairLoss(i, estimate), i);
  std::vector<std::size_t> inliers;
  for (const auto& [value, i] : scored) {
    if (value <= threshold_px) inliers.push_back(i);
  }
  if (inliers.size() * 2 < n) {
    std::stable_sort(scored.begin(), scored.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    inliers.clear();
    for (std::size_t k = 0; k < (n + 1) / 2; ++k) inliers.push_back(scored[k].second);
    std::sort(inliers.begin(), inliers.end());
  }
  return inliers;
}

double shareWithinThreshold(const LossEvaluator& loss, const Extrinsic& estimate, double threshold_px) {
  const std::size_t n = loss.pairCount();
  std::size_t within = 0;
  for (std::size_t i = 0; i < n; ++i) within += loss.pairLoss(i, estimate) <= threshold_px ? 1 : 0;
  return n == 0 ? 0.0 : static_cast<double>(within) / static_cast<double>(n);
}

}  // namespace thermal_lidar_calibration
