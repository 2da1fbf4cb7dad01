#pragma once
// Beyond the paper (issue 21): the coarse search for the camera time offset delta before the
// joint refinement. While the vehicle drives straight at one speed, a late image looks like a
// camera mounted further forward, so the pose found at delta = 0 absorbs most of the offset and
// a local search from there can stop in the shallow valley between the two. So the pose is
// refined at the deltas of a grid over +-max_s (each from its neighbour's pose: a continuation;
// every 4th point first, then every point around the best of those), and the delta with the
// lowest loss after refinement (the profile's minimum) starts the joint refinement. The profile is
// kept for the report: a flat profile is a drive that cannot tell the offset from the translation.
//
// A refit that starts where an earlier fit's estimate ended (the association rounds) has its
// valley already: it walks the grid downhill from the start only (OffsetSearchReach::kNearStart).

#include "thermal_lidar_calibration/core/calibration_config.hpp"
#include "thermal_lidar_calibration/core/extrinsic.hpp"
#include "thermal_lidar_calibration/core/loss.hpp"

#include <cstdint>
#include <functional>
#include <vector>

namespace thermal_lidar_calibration {

struct TimeOffsetProfile {
  std::vector<double> offsets_s;  // the grid, ascending
  std::vector<double> losses;     // after refining the pose there; infinite where not visited
  std::vector<Extrinsic> poses;   // that pose
  std::size_t best = 0;           // index of the lowest loss
  std::uint64_t evaluations = 0;
  bool stopped = false;
};

enum class OffsetSearchReach {
  kWholeRange,  // the grid over +-max_s, as above
  // From the start's grid point one point at a time to either side, each refined from the one
  // before, while the loss falls: the grid point the whole range would find when the profile has
  // one valley, reached with three refinements instead of about twenty when the start lies in it
  // (and then the same poses, so the same result).
  kNearStart,
};

// Called after each grid point with (done, total); return false to stop.
using ProfileCallback = std::function<bool(int done, int total, double best_loss)>;

// `loss` must have a time offset (its config's time_offset_s is where the grid walk starts).
// Throws std::invalid_argument on a bad config or an evaluator without a time offset.
TimeOffsetProfile searchTimeOffset(const LossEvaluator& loss, const Extrinsic& start,
                                   const std::vector<std::size_t>& pairs,
                                   const TimeOffsetConfig& timing, const RefineConfig& refine,
                                   int threads, const ProfileCallback& callback = {},
                                   OffsetSearchReach reach = OffsetSearchReach::kWholeRange);

}  // namespace thermal_lidar_calibration
