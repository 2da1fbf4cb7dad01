#pragma once
// The calibration the user already has, beside ours (the comparison of the paper's Table 2):
// the difference per camera axis and both transforms' Eq. (3) loss on the same pairs. Where an
// uncertainty is known, whether each axis' difference lies within its 95 % interval.

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "thermal_lidar_calibration/core/extrinsic.hpp"
#include "thermal_lidar_calibration/core/loss.hpp"
#include "thermal_lidar_calibration/core/pose_difference.hpp"
#include "thermal_lidar_calibration/core/uncertainty.hpp"

namespace thermal_lidar_calibration {

struct ReferenceComparison {
  std::string source;  // "file" or "tf"
  std::string origin;  // the file's path, or "tf velodyne -> thermal_optical"
  Extrinsic reference;
  PoseDifference difference;    // ours relative to the reference (pose_difference.hpp)
  double reference_loss = 0.0;  // Eq. (3), paper's nearest rule, on the pairs ours used
  double our_loss = 0.0;        // the same for ours
  std::size_t pairs = 0;
  // Per axis (rotation x, y, z, translation x, y, z): |difference| <= the half-width. Set only
  // when an uncertainty was given.
  std::optional<std::array<bool, 6>> within_uncertainty;
};

// `nearest` is the evaluator of the collected pairs (its pixel rule is replaced by the paper's
// nearest-pixel one); `used` the pairs ours used.
ReferenceComparison compareWithReference(const LossEvaluator& nearest, const Extrinsic& ours,
                                         const Extrinsic& reference,
                                         const std::vector<std::size_t>& used,
                                         const std::optional<Uncertainty>& uncertainty);

}  // namespace thermal_lidar_calibration
