#pragma once
// Where, in a time-ordered window, the pairs stop fitting the old extrinsic and start fitting
// the new one: the split that maximises the number of "new fits better" minus "old fits
// better" pairs after it. Signs, not sizes: a mismatched pair with a huge loss difference counts
// once, like any other.

#include <cstddef>
#include <vector>

namespace thermal_lidar_calibration {

// `differences[i]` = loss at the old extrinsic - loss at the new one, pair i in time order.
// Returns k in [0, n - min_after] maximising sum_{i >= k} sign(differences[i]); among equal
// sums the latest k (fewer old pairs taken for new ones). 0 when n <= min_after.
std::size_t signChangePoint(const std::vector<double>& differences, std::size_t min_after);

}  // namespace thermal_lidar_calibration
