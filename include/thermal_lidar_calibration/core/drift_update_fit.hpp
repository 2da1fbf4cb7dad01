#pragma once
// The new extrinsic after a confirmed change (drift_monitor.hpp), fitted on the pairs since the
// change: the simplest motion of the camera that explains them. A turn about the camera's own
// centre or a shift without a turn, whichever predicts pairs it was not fitted on better; the
// full 6-DOF pose only when it predicts them better still, significantly.
//
// Why not always the full pose: a few dozen pairs of people at 10-40 m pin down where they sit
// in the image, but hardly how that splits between a turn and a shift of the camera (both move
// far people alike; only the spread of their ranges tells them apart), and a full fit wanders
// along that valley: on the synthetic bump drives, 60 pairs after a 0.5 deg turn left full fits
// 1-3 cm (once 16 cm) from the new truth, the turn alone 0.3-0.6 cm. The comparisons are
// cross-fitted, as the window test: each fold's pairs are scored by fits made without them,
// pairs no model explains are left out; turn against shift by the Hodges-Lehmann centre of the
// turn's held-out loss minus the shift's (a tie keeps the turn), the simpler against the full
// pose by a one-sided signed-rank test.

#include "thermal_lidar_calibration/core/calibration_config.hpp"
#include "thermal_lidar_calibration/core/calibration_pair.hpp"
#include "thermal_lidar_calibration/core/camera_model.hpp"
#include "thermal_lidar_calibration/core/drift_config.hpp"
#include "thermal_lidar_calibration/core/extrinsic.hpp"
#include "thermal_lidar_calibration/core/local_fit.hpp"
#include "thermal_lidar_calibration/core/loss.hpp"

#include <cstdint>
#include <vector>

namespace thermal_lidar_calibration {

enum class DriftUpdateModel : std::uint8_t { kTurn, kShift, kFull };
const char* toString(DriftUpdateModel model);  // "turn", "shift", "full"

struct DriftUpdateFit {
  LocalFit fit;  // the chosen model's (its inliers among the pairs)
  DriftUpdateModel model = DriftUpdateModel::kFull;
  // Held-out: the full pose beats the simpler model (one-sided signed-rank); 0 when the full
  // pose is always taken (monitor_update_full_significance 1).
  double full_p_value = 1.0;
  std::uint64_t evaluations = 0;  // loss evaluations of all fits
};

// `reference`: the extrinsic in use; `start`: the best guess of the new one (the confirming
// window's fit or the previous candidate). The full fit starts there, the turn at its rotation
// about the reference's camera centre, the shift at the reference. Deterministic whatever the
// thread count. Throws std::invalid_argument on a bad config or fewer than 2 * folds pairs.
DriftUpdateFit fitDriftUpdate(const CameraModel& camera, const std::vector<CalibrationPair>& pairs,
                              const Extrinsic& reference, const Extrinsic& start,
                              const DriftConfig& drift, const CalibrationConfig& calibration);
// The same on the pairs of `nearest` (an evaluator with PixelRule::kNearest the caller already
// has: the distance maps are built once).
DriftUpdateFit fitDriftUpdate(const LossEvaluator& nearest, const Extrinsic& reference,
                              const Extrinsic& start, const DriftConfig& drift,
                              const CalibrationConfig& calibration);

}  // namespace thermal_lidar_calibration
