#include "thermal_lidar_calibration/core/time_offset_search.hpp"

#include "thermal_lidar_calibration/core/local_refinement.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace thermal_lidar_calibration {
namespace {

// Each grid point's refinement stops at a coarser step than the final one: it only has to rank
// the grid points, and the joint refinement from the best of them finishes the job.
RefineConfig coarseRefine(const RefineConfig& refine) {
  RefineConfig c = refine;
  c.min_step_rot_rad = std::max(refine.min_step_rot_rad, 2e-5);  // ~0.001 deg
  c.min_step_trans_m = std::max(refine.min_step_trans_m, 1e-4);
  c.min_step_rot_rad = std::min(c.min_step_rot_rad, c.initial_step_rot_rad);
  c.min_step_trans_m = std::min(c.min_step_trans_m, c.initial_step_trans_m);
  c.max_evaluations = std::min(refine.max_evaluations, 3000);
  return c;
}

}  // namespace

TimeOffsetProfile searchTimeOffset(const LossEvaluator& loss, const Extrinsic& start,
                                   const std::vector<std::size_t>& pairs,
                                   const TimeOffsetConfig& timing, const RefineConfig& refine,
                                   int threads, const ProfileCallback& callback, OffsetSearchReach reach) {
  timing.validate();
  refine.validate();
  if (!loss.config().time_offset_s) {
    throw std::invalid_argument("time offset search: the loss has no time offset to move points with");
  }
  const double start_offset = *loss.config().time_offset_s;
  // The grid: every coarse step from -max to +max, through the starting offset.
  const int below = static_cast<int>(std::floor((start_offset + timing.max_s) / timing.coarse_step_s + 1e-9));
  const int above = static_cast<int>(std::floor((timing.max_s - start_offset) / timing.coarse_step_s + 1e-9));
  TimeOffsetProfile profile;
  for (int k = -below; k <= above; ++k) profile.offsets_s.push_back(start_offset + k * timing.coarse_step_s);
  const std::size_t n = profile.offsets_s.size();
  const std::size_t origin = static_cast<std::size_t>(below);
  profile.losses.assign(n, std::numeric_limits<double>::infinity());
  profile.poses.assign(n, start);

  const RefineConfig coarse = coarseRefine(refine);
  int done = 0;
  std::vector<char> visited(n, 0);
  const auto bestLoss = [&] { return *std::min_element(profile.losses.begin(), profile.losses.end()); };
  const auto refineAt = [&](std::size_t i, const Extrinsic& from) {
    const LossEvaluator at = loss.withTimeOffset(profile.offsets_s[i]);
    const RefineOutcome r = LocalRefinement(at, coarse, threads).run(from, pairs);
    profile.poses[i] = r.best;
    profile.losses[i] = r.loss;
    profile.evaluations += r.evaluations;
    visited[i] = 1;
    ++done;
    // A walk near the start ends where the loss stops falling, not at the grid's end: its total
    // is always one step ahead until it ends (below), so a progress line never shows 3/41 left.
    const int total = reach == OffsetSearchReach::kNearStart ? done + 1 : static_cast<int>(n);
    if (callback && !callback(done, total, bestLoss())) profile.stopped = true;
  };
  // Walks from `from` to `to` (inclusive) one grid point at a time, each refined from the pose
  // of the point before it, every `stride`-th point only.
  const auto walk = [&](std::size_t from, std::size_t to, std::size_t stride) {
    std::size_t previous = from;
    const bool up = to >= from;
    for (std::size_t i = from; !profile.stopped;) {
      if (!visited[i]) refineAt(i, profile.poses[previous]);
      previous = i;
      if (i == to) break;
      const std::size_t gap = up ? to - i : i - to;
      const std::size_t next_step = std::min(stride, gap);
      i = up ? i + next_step : i - next_step;
    }
  };
  const auto lowest = [&] {
    return static_cast<std::size_t>(std::min_element(profile.losses.begin(), profile.losses.end()) -
                                    profile.losses.begin());
  };
  refineAt(origin, start);
  if (reach == OffsetSearchReach::kNearStart) {
    // Upwards while the loss falls; downwards only when the first step up did not fall. The first
    // step each way is refined from the start's pose, as the whole range's fine walk does.
    for (const int direction : {+1, -1}) {
      std::size_t i = origin;
      while (!profile.stopped && (direction > 0 ? i + 1 < n : i > 0)) {
        const std::size_t next = direction > 0 ? i + 1 : i - 1;
        refineAt(next, profile.poses[i]);
        if (!(profile.losses[next] < profile.losses[i])) break;
        i = next;
      }
      if (i != origin) break;
    }
    if (!profile.stopped && callback && !callback(done, done, bestLoss())) profile.stopped = true;
    profile.best = profile.stopped ? origin : lowest();
    return profile;
  }
  // Coarse to fine: every kStride-th grid point outwards from the start, then every point within
  // kStride of the best of those. The profile is smooth over this scale (the pose follows the
  // offset), so the best coarse point's neighbourhood holds the minimum.
  constexpr std::size_t kStride = 4;
  walk(origin, n - 1, kStride);
  walk(origin, 0, kStride);
  if (profile.stopped) {
    profile.best = origin;
    return profile;
  }
  const std::size_t coarse_best = lowest();
  walk(coarse_best, std::min(n - 1, coarse_best + kStride), 1);
  walk(coarse_best, coarse_best >= kStride ? coarse_best - kStride : 0, 1);
  profile.best = profile.stopped ? coarse_best : lowest();
  return profile;
}

}  // namespace thermal_lidar_calibration
