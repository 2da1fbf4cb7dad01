#pragma once
// Splits an object that is too big for one person into the people it may hold:
//  - by horizontal gaps: PCL Euclidean cluster extraction (KD-tree) on the object's points
//    projected to the ground, so a person beside a pole, a vehicle or another person with a
//    gap of split_tolerance_m comes apart (clustering in 2-D ignores the vertical gaps between
//    rings, which reach ~0.5 m at 20 m);
//  - by heads: people touching side by side show as two peaks in the height profile across the
//    line of sight; the object is cut at the valley between peaks that dips head_dip_m below both.

#include "thermal_lidar_calibration/detection/lidar_detector_config.hpp"

#include <Eigen/Core>

#include <vector>

namespace thermal_lidar_calibration {
namespace detection {

// Parts of `object` (indices into levelled) separated by horizontal gaps > tolerance_m; parts
// ordered by size (largest first), each in ascending index order.
std::vector<std::vector<int>> splitByGaps(const std::vector<Eigen::Vector3f>& levelled,
                                          const std::vector<int>& object, double tolerance_m);

// Parts of `object` between the valleys of its height profile across the line of sight
// (bins of bin_m); a single part when there is no valley dip_m below the peaks on both sides.
std::vector<std::vector<int>> splitByHeads(const std::vector<Eigen::Vector3f>& levelled,
                                           const std::vector<float>& heights, const std::vector<int>& object,
                                           double bin_m, double dip_m);

}  // namespace detection
}  // namespace thermal_lidar_calibration
