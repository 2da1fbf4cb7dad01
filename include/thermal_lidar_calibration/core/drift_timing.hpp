#pragma once
// The drift watch and the camera's time offset (issue 21). A camera driver restarted with another
// latency shifts every image in time; on a drive the people move relative to the LiDAR, so the
// reference no longer fits and a window test sees a "change". Before calling it an extrinsic
// drift, the watch asks whether the reference extrinsic fits again at another time offset alone:
// a 1-D search over the offset change with the pose held. If that explains the window about as
// well as the window's own fit of the pose (or, when the pose test sees no change, lowers the
// loss as much as a change must), the change is timing, reported apart from the extrinsic.
// ROS-free.

#include "thermal_lidar_calibration/core/calibration_pair.hpp"
#include "thermal_lidar_calibration/core/camera_model.hpp"
#include "thermal_lidar_calibration/core/extrinsic.hpp"

#include <cmath>
#include <optional>
#include <vector>

namespace thermal_lidar_calibration {

struct TimingChangeFit {
  double change_s = 0.0;        // the offset change that fits the window best, pose held
  double loss = 0.0;            // Eq. (3), nearest rule, at the reference with that change
  double loss_reference = 0.0;  // the same without the change
  double loss_fit = 0.0;        // the same at the window's own fit of the pose
  // What the change explains of what the window's fit gains: (reference - loss) /
  // (reference - fit), 0 when the fit gains nothing.
  double explained() const {
    return loss_reference > loss_fit ? (loss_reference - loss) / (loss_reference - loss_fit) : 0.0;
  }
  std::size_t pairs_with_motion = 0;
  std::size_t pairs_used = 0;   // those the reference or the fit explains within the threshold
  // Whether the best change lies inside the searched range (one at its edge is no minimum).
  bool interior(double max_change_s) const { return std::abs(change_s) < max_change_s - 0.0025; }
};

// The pairs as the watch holds them: moved to their image's instant at the reference's time
// offset, so that a further change d moves each point by its velocity times d. Searched within
// +-max_change_s (steps of 5 ms, then refined to 0.5 ms), on the pairs whose Eq. (1) loss at the
// reference or at `fit` is within `threshold_px`. nullopt when no pair has motion or none is
// explained.
std::optional<TimingChangeFit> fitTimingChange(const CameraModel& camera, const std::vector<CalibrationPair>& window,
                                               const Extrinsic& reference, const Extrinsic& fit,
                                               double max_change_s, double behind_camera_penalty_c1,
                                               double threshold_px);

// `pair` with its points at its image's instant for `time_offset_s`, rebased so that a further
// offset d moves them by velocity times d (cloud stamp = image stamp, no per-point times); the
// velocities are kept. Unchanged without measured motion.
CalibrationPair rebasedAtTimeOffset(CalibrationPair pair, double time_offset_s);

}  // namespace thermal_lidar_calibration
