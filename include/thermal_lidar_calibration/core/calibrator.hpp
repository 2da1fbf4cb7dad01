#pragma once
// The calibration entry point: a dataset and a config in, a result struct out.
// Never logs, sleeps or reads parameters; progress leaves through a callback that may stop it.

#include "thermal_lidar_calibration/core/calibration_config.hpp"
#include "thermal_lidar_calibration/core/calibration_pair.hpp"
#include "thermal_lidar_calibration/core/camera_model.hpp"
#include "thermal_lidar_calibration/core/extrinsic.hpp"
#include "thermal_lidar_calibration/core/time_offset_search.hpp"
#include "thermal_lidar_calibration/core/vertical_centring.hpp"

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace thermal_lidar_calibration {

struct Progress {
  std::string stage;            // "outlier_fit 1/2", "final_fit", "plain_fit", "refine"
  int generation = 0;           // within the stage (refine: iteration)
  int generations_total = 0;
  double best_loss = 0.0;       // Eq. (3) of the best individual of the stage so far, pixels
  std::uint64_t evaluations = 0;  // loss evaluations so far, all stages
  Extrinsic best;
};
// Return false to ask the calibration to stop; it then returns its best so far (stopped = true).
using ProgressCallback = std::function<bool(const Progress&)>;

// One point of the convergence history: the best loss after a generation of a stage, then
// after each refinement iteration (for the report's convergence plot).
struct ConvergenceStep {
  std::string stage;  // "outlier_fit 1/2", "final_fit", "plain_fit", "refine 1", "refine 2", ...
  int step = 0;       // generation within the stage (refine: iteration, 0 = its start)
  double best_loss = 0.0;  // Eq. (3) px: nearest rule for the evolution, sub-pixel for refine
  std::uint64_t evaluations = 0;  // loss evaluations so far, all stages
};

struct CalibrationResult {
  Extrinsic extrinsic;            // final (refined unless refine = none)
  double loss = 0.0;              // Eq. (3), paper's nearest-pixel rule, on the pairs used
  double loss_bilinear = 0.0;     // Eq. (3) with the sub-pixel rule, on the pairs used
  Extrinsic evolution_extrinsic;  // result of Algorithm 1/2 before refinement
  double evolution_loss = 0.0;    // its Eq. (3), nearest rule, on the pairs used
  // The default run's fit after its shortened evolution (CalibrationConfig::evolutionRun) failed
  // Algorithm 2's test on all the pairs, so a fit after the paper's full length was run too and
  // the one passing it better kept (calibrator.cpp's calibrate()).
  bool evolution_full_length = false;
  std::vector<double> pair_losses;  // Eq. (1), nearest rule, every input pair at `extrinsic`
  // The pairs used: Algorithm 2's isInlier (all true for Algorithm 1); with refine = local,
  // re-selected after refinement among all pairs by Eq. (1) <= threshold_sample_px.
  std::vector<bool> inliers;
  // With refine = local, the vertical centring after the refinement (vertical_centring.hpp):
  // `extrinsic` is its result; applied = false (and why) when it was skipped.
  VerticalCentringOutcome vertical_centring;
  // With refine = local and refine.ring_alias_turns > 0 (ring_alias.hpp): the rings' elevation
  // spacing found among the points used (0: none found, nothing tried), the turned starts
  // refined, and the turn of the start whose refined fit was kept, in ring spacings (+ turns the
  // camera down about its x axis; 0: the refined pose stayed; the kept fit may end near the
  // refined pose, lower in the same basin). After association rounds (association_refit.hpp):
  // every fit's starts, and the last turn any of them kept.
  double ring_spacing_rad = 0.0;
  int ring_alias_tried = 0;
  int ring_alias_turn = 0;
  // With refine = local and refine.ring_end_weight > 0 (ring_ends.hpp): the rings' ends the
  // refinement read against their own people's outlines, over all pairs (0: none).
  std::size_t ring_ends = 0;
  std::size_t pairs_used = 0;
  std::size_t pairs_collected = 0;
  int outlier_fits_accepted = 0;    // Algorithm 2 fits with ratio_inliers >= ratio_solution
  std::uint64_t evaluations = 0;    // Eq. (3) evaluations
  std::uint64_t points_projected = 0;
  bool stopped = false;             // the callback asked to stop
  // Best loss per generation of every stage, then the refinement rounds' iterations. The outlier
  // fits run on subsets of the pairs and the refinement on the sub-pixel loss, so losses are
  // comparable within a stage, not across stages.
  std::vector<ConvergenceStep> history;
  double seconds = 0.0;             // wall time of calibrate()
  // Issue 21: the camera time offset the result holds (INTERFACE.md, time_offset_s).
  TimeOffsetMode time_offset_mode = TimeOffsetMode::kNone;   // as applied
  TimeOffsetMode time_offset_asked = TimeOffsetMode::kNone;  // as configured
  double time_resolution_ms = 0.0;  // mode estimate: how well the pairs resolve it (before the search)
  double time_offset_s = 0.0;       // estimated or fixed; 0 when none was applied
  std::string time_offset_note;     // why the applied mode differs from the one asked for
  std::size_t pairs_with_motion = 0;  // pairs whose people's motion was measured
  // The coarse search over the whole range (mode estimate): each grid offset and the loss after
  // refining the pose there (bilinear rule), on the time_offset_profile_pairs pairs then used (with
  // association, those of the first fit that searched the whole range: the later rounds search
  // near its estimate).
  std::vector<double> time_offset_profile_s, time_offset_profile_loss;
  std::size_t time_offset_profile_pairs = 0;
  // The loss with the points where they were captured (no time offset), to show what timing
  // changed; equal to `loss` with time_offset_mode none.
  double loss_without_timing = 0.0;
};

// Throws std::invalid_argument on an invalid config, no pairs, too few pairs for Algorithm 2
// (needs more than min_sample), or pairs that do not match the camera.
CalibrationResult calibrate(const CameraModel& camera, const std::vector<CalibrationPair>& pairs,
                            const CalibrationConfig& config,
                            const ProgressCallback& progress = {});

// Beyond the paper (issue 23): the refinement stage alone, from a known extrinsic and the time
// offset it goes with (the start of the search when time_offset_mode is estimate), as
// calibrate() refines Algorithm 2's fit. The first inliers are the pairs within
// threshold_sample_px of `start` (at least the better half). The result's evolution_* fields
// hold the start. An estimate not told from the start is kept at the start only when that is the
// config's time_offset_s (time_offset.keep_start_sigmas), not when a later round starts where an
// earlier one's estimate ended. `reach`: how far the coarse search over the offset looks
// (time_offset_search.hpp); with kNearStart the result has no profile of its own (the caller
// keeps the one of the fit that searched the whole range). Throws std::invalid_argument as
// calibrate() does, and for refine none.
CalibrationResult refineFrom(const CameraModel& camera, const std::vector<CalibrationPair>& pairs,
                             const CalibrationConfig& config, const Extrinsic& start, double start_time_offset_s,
                             const ProgressCallback& progress = {},
                             OffsetSearchReach reach = OffsetSearchReach::kWholeRange);

}  // namespace thermal_lidar_calibration
