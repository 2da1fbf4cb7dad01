#include "thermal_lidar_calibration/core/reference_comparison.hpp"

#include <cmath>
#include <stdexcept>

namespace thermal_lidar_calibration {

ReferenceComparison compareWithReference(const LossEvaluator& loss, const Extrinsic& ours,
                                         const Extrinsic& reference,
                                         const std::vector<std::size_t>& used,
                                         const std::optional<Uncertainty>& uncertainty) {
  if (used.empty()) throw std::invalid_argument("reference comparison: no pairs used");
  const LossEvaluator nearest = loss.withPixelRule(PixelRule::kNearest);
  ReferenceComparison c;
  c.reference = reference;
  c.difference = poseDifference(ours, reference);
  c.reference_loss = nearest.loss(reference, used);
  c.our_loss = nearest.loss(ours, used);
  c.pairs = used.size();
  if (uncertainty && uncertainty->resamples >= 2) {
    const Vector6d d = asVector(c.difference);
    std::array<bool, 6> within{};
    for (int k = 0; k < 6; ++k) within[k] = std::abs(d[k]) <= uncertainty->halfWidth(k);
    c.within_uncertainty = within;
  }
  return c;
}

}  // namespace thermal_lidar_calibration
