#pragma once
// Beyond the paper (default run, after the local refinement): the centre of the poses that fit.
//
// Eq. (3) charges a point only for lying outside the person mask, so every pose that keeps the
// points inside the masks costs the same. A person's mask marks the pixels whose centre the
// person covers, so the person's true outline runs up to half a pixel beyond the outermost
// marked centres; LiDAR points on the outline (each ring's left and right ends) therefore cost a
// fraction of a pixel at the true pose, and the sub-pixel loss is lowest where the silhouettes
// are wider: above the truth on one rig and below it on another, depending on where the rings
// cross the people, and always along the image vertical (a ring gap of ~18 px leaves that
// direction otherwise unconstrained). On five clean MS2-like synthetic drives the refined
// estimate sat 1.5-3.7 cm along camera y and 0.06-0.18 deg about x from the truth, and the
// sub-pixel loss's minimum was the same whether searched from the truth or from the estimate:
// a bias of the minimum, not a search that stopped early (docs/validation/accuracy.md).
//
// With every mask grown by one pixel (margin_px) the true pose fits all points, and the poses
// that fit form a region around it whose edges are set by the ring gaps and the points' inset
// from the outline, alike on both sides; its centre is the estimate (the midrange estimator of
// a uniform error). Only the image-vertical plane is centred, the other four axes keep the
// refinement's values: moving the camera back along its axis shrinks every projection, so the
// region reaches much farther that way and its centre would be pulled along.
//
// The plane: a rotation about the camera's x axis through the pivot (the points' centroid) and a
// translation along the camera's y axis, both scaled to pixels at the pivot's depth. The region
// {loss <= best * (1 + tolerance) + 1e-5} is traced by bisection along `rays` directions from
// its current centre and replaced by the centroid of that polygon, `iterations` times.

#include "thermal_lidar_calibration/core/calibration_config.hpp"
#include "thermal_lidar_calibration/core/calibration_pair.hpp"
#include "thermal_lidar_calibration/core/camera_model.hpp"
#include "thermal_lidar_calibration/core/extrinsic.hpp"
#include "thermal_lidar_calibration/core/loss.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace thermal_lidar_calibration {

struct VerticalCentringOutcome {
  VerticalCentringConfig config;  // as run
  Extrinsic extrinsic;            // the centre, or the start when not applied
  bool ran = false;               // the stage was run (default run, enabled)
  bool applied = false;           // and moved the estimate to the centre
  // Why not: "" when applied; "disabled", "points do not fit the grown masks", "region unbounded",
  // "pivot behind the camera".
  std::string skipped_because = "disabled";
  double best_cost_px = 0.0;    // Eq. (3) with the grown masks at the plane's best pose
  double shift_rotation_px = 0.0;     // the move, rotation part (pixels at the pivot's depth)
  double shift_translation_px = 0.0;  // the move, translation part
  std::uint64_t evaluations = 0;
};

// The pairs' masks grown by `margin_px` (L1: each step adds the 4-neighbours), read with the
// sub-pixel rule: the loss the centring traces. Same pair indices as `pairs`. With
// `time_offset_s`, the points are moved to the image's instant as in the refinement (loss.hpp).
LossEvaluator grownMaskEvaluator(const CameraModel& camera,
                                 const std::vector<CalibrationPair>& pairs, int margin_px,
                                 double behind_camera_penalty_c1,
                                 std::optional<double> time_offset_s = std::nullopt);

// Centres `start` over `pairs` (indices into `grown`, duplicates allowed) as described above.
// Evaluations run `threads` wide (0 = all cores); the result does not depend on it.
VerticalCentringOutcome centreVertically(const LossEvaluator& grown, const Extrinsic& start,
                                         const std::vector<std::size_t>& pairs,
                                         const VerticalCentringConfig& config, int threads);

}  // namespace thermal_lidar_calibration
