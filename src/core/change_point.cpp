#include "thermal_lidar_calibration/core/change_point.hpp"

namespace thermal_lidar_calibration {

std::size_t signChangePoint(const std::vector<double>& differences, std::size_t min_after) {
  const std::size_t n = differences.size();
  if (n <= min_after) return 0;
  // Suffix sums of the signs, scanned from the end so that ties keep the latest split.
  long suffix = 0;
  for (std::size_t i = n; i > n - min_after; --i) {
    const double d = differences[i - 1];
    suffix += (d > 0) - (d < 0);
  }
  long best_sum = suffix;
  std::size_t best = n - min_after;
  for (std::size_t k = n - min_after; k > 0; --k) {
    const double d = differences[k - 1];
    suffix += (d > 0) - (d < 0);
    if (suffix > best_sum) {
      best_sum = suffix;
      best = k - 1;
    }
  }
  return best;
}

}  // namespace thermal_lidar_calibration
