#pragma once
// good / usable / collect_more, from the uncertainty per axis and the coverage, with one line
// per finding that says what was wrong and what to do ("no people in the left third of the
// image: have people walk there"). Thresholds are configurable (quality_* parameters).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "thermal_lidar_calibration/core/coverage.hpp"
#include "thermal_lidar_calibration/core/parameter_range.hpp"
#include "thermal_lidar_calibration/core/timing_check.hpp"
#include "thermal_lidar_calibration/core/uncertainty.hpp"

namespace thermal_lidar_calibration {

enum class Verdict : std::uint8_t { kGood = 0, kUsable = 1, kCollectMore = 2 };
const char* toString(Verdict verdict);  // "good", "usable", "collect_more"

struct VerdictConfig {
  // Uncertainty: the largest 95 % half-width over the axes.
  double good_rotation_deg = 0.1;
  double good_translation_cm = 2.0;
  double usable_rotation_deg = 0.3;
  double usable_translation_cm = 5.0;
  // Pairs used.
  int good_pairs = 40;
  int usable_pairs = 20;
  // Each horizontal third of the image should hold this fraction of the person pixels: below
  // `usable_third_fraction` the verdict is collect_more, below `good_third_fraction` usable.
  double usable_third_fraction = 0.03;
  double good_third_fraction = 0.10;
  // People both near and far (coverage near_far_split_m): at least this many of each.
  int min_people_near = 3;
  int min_people_far = 3;
  // Distinct places people stood (relative to the sensors).
  int good_distinct_positions = 15;
  int usable_distinct_positions = 8;
  // The fit's Eq. 3 loss on the pairs it used, px: above this the people's points lie off their
  // masks (a fit of 0.03-0.2 px is typical; fits carried by mismatched pairs or a failed search
  // measured 2.6-24 px), whatever the intervals say.
  double max_loss_px = 1.0;
  // Timing (issue 21). The estimated time offset's 95 % half-width, ms: good / usable.
  double good_time_offset_ms = 5.0;
  double usable_time_offset_ms = 20.0;
  // The drive must resolve the offset to this (1 sigma, ms, timing_check.hpp) for a good
  // verdict while estimating it; beyond usable_time_offset_ms it is collect_more. At the
  // estimation gate (time_offset_max_resolution_ms, 5): a drive that resolves the offset well
  // enough to estimate it is judged by the estimate's own interval (good_time_offset_ms), which
  // the bootstrap measures with the translation along the travel. At 3 ms every field drive of
  // the timing validation (resolution 2.9-4.6 ms, offsets within 5 ms of the truth) was told to
  // drive differently.
  double good_time_resolution_ms = 5.0;
  // Offset not estimated: a joint refinement from the fit that moves the offset by at least this
  // (ms) and lowers the loss by at least `timing_min_gain` (fraction) names timing.
  double timing_probe_ms = 10.0;
  double timing_min_gain = 0.1;
  static const ParameterRanges<VerdictConfig>& ranges();  // checked by validate()
  void validate() const;  // throws std::invalid_argument naming the key and range
};

struct VerdictReport {
  Verdict verdict = Verdict::kCollectMore;
  // One line per finding, worst first: "what: what to do". When all is well, one line saying so.
  std::vector<std::string> reasons;
  // The image thirds with too few people (names from imageThirdName), for the node's status.
  std::vector<std::string> missing_regions;
};

// `uncertainty` may be absent (while collecting, before a fit): then only coverage and pairs
// decide, and the verdict is at best usable. `fit_loss_px`: the fit's Eq. 3 loss on the pairs it
// used, when there is a fit.
// `timing`: the fit's timing assessment, when the pairs' motion was measured.
VerdictReport judgeQuality(const Coverage& coverage, const std::optional<Uncertainty>& uncertainty,
                           const VerdictConfig& config, std::optional<double> fit_loss_px = std::nullopt,
                           const std::optional<TimingAssessment>& timing = std::nullopt);

}  // namespace thermal_lidar_calibration
