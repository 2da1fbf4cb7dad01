#pragma once
// Beyond the paper (switchable, refine: none|local): the evolutionary search stops within about
// its mutation step of the loss minimum. This derivative-free pattern search (Hooke-Jeeves style:
// +-step probes on each of the six parameters, a combined move along every improving axis, step
// halving when nothing improves) converges to the minimum of the sub-pixel (bilinear) loss, which
// unlike the nearest-pixel loss is continuous and so does not stall the search. It searches
// over the rotation and the camera-frame position of the data's centroid rather than over
// (r, t), so that rotation and translation steps do not undo each other (see the .cpp).

#include "thermal_lidar_calibration/core/calibration_config.hpp"
#include "thermal_lidar_calibration/core/extrinsic.hpp"
#include "thermal_lidar_calibration/core/loss.hpp"

#include <cstdint>
#include <functional>
#include <vector>

namespace thermal_lidar_calibration {

struct RefineOutcome {
  Extrinsic best;
  double loss = 0.0;     // Eq. (3) with the evaluator's pixel rule, at `best`
  int iterations = 0;
  std::uint64_t evaluations = 0;
  bool converged = false;  // steps shrank below the minimum (not stopped by the budget)
  bool stopped = false;
};

using RefineCallback = std::function<bool(int iteration, double loss, const Extrinsic& best,
                                          std::uint64_t evaluations)>;

// What the search may change (the drift watch's simpler models of a bump, drift_update_fit.hpp).
// kCameraTurn: only the rotation, about the camera's own centre (R' = D R, t' = D t for a turn
// D: the camera stays where it is). kCameraShift: only the translation (the camera moves
// without turning).
enum class RefineFreedom : std::uint8_t { kFull, kCameraTurn, kCameraShift };

class LocalRefinement {
 public:
  // `loss` (normally the bilinear evaluator) must outlive the refinement.
  LocalRefinement(const LossEvaluator& loss, RefineConfig config, int threads,
                  RefineFreedom freedom = RefineFreedom::kFull);
  RefineOutcome run(const Extrinsic& start, const std::vector<std::size_t>& pairs,
                    const RefineCallback& callback = {}) const;

 private:
  const LossEvaluator& loss_;
  RefineConfig config_;
  int threads_;
  RefineFreedom freedom_;
};

}  // namespace thermal_lidar_calibration
