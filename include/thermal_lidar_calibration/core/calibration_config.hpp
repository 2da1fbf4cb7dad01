#pragma once
// Every hyper-parameter of the calibration, defaults = the paper's Table 1 in SI units.
// Each struct's validate() throws std::invalid_argument naming the key, value and allowed range.

#include "thermal_lidar_calibration/core/loss.hpp"
#include "thermal_lidar_calibration/core/parameter_range.hpp"

#include <cstdint>

namespace thermal_lidar_calibration {

// Algorithm 1 (evolutionary search).
struct EvolutionConfig {
  int population_size = 500;            // N_pop
  int max_iterations = 400;             // iter_max (generations)
  double rotation_interval_rad = 3.5;   // initial r_i ~ U(-a, a)
  double translation_interval_m = 1.0;  // initial t_i ~ U(-a, a)
  double elite_fraction = 0.15;         // pct_elite
  double crossover_fraction = 0.40;     // pct_crossover
  int initial_population_factor = 5;    // c2: the first population has c2 * N_pop individuals
  double sigma_rot_rad = 0.02;          // mutation noise U(-s, s) per rotation component
  double sigma_trans_m = 0.02;          // mutation noise U(-s, s) per translation component
  double min_inside_fraction = 0.5;     // initial individual kept if some pair projects >= this
  static const ParameterRanges<EvolutionConfig>& ranges();  // checked by validate()
  void validate() const;
};

// Algorithm 2 (outlier rejection around Algorithm 1).
struct OutlierConfig {
  int min_sample_large = 20;        // min_sample when |D| >= min_sample_switch
  int min_sample_small = 15;        // min_sample otherwise
  int min_sample_switch = 40;       // |D| at which the larger subset is used
  int iterations = 2;               // iter_outlier
  double ratio_solution = 0.7;      // accept a fit if this fraction of D_val is within threshold
  double threshold_px = 2.0;        // threshold_sample, Eq. (1) pixels (MS2 rig: 1.5)
  int minSample(std::size_t pairs) const {
    return static_cast<int>(pairs) >= min_sample_switch ? min_sample_large : min_sample_small;
  }
  static const ParameterRanges<OutlierConfig>& ranges();  // checked by validate()
  void validate() const;
};

enum class Algorithm : std::uint8_t { kPlain = 1, kOutlierRejection = 2 };
enum class RefineMode : std::uint8_t { kNone, kLocal };

// Beyond the paper: derivative-free local search on the bilinear loss after the evolution.
struct RefineConfig {
  RefineMode mode = RefineMode::kLocal;
  double initial_step_rot_rad = 0.02;    // first probe size (about the mutation noise)
  double initial_step_trans_m = 0.02;
  double min_step_rot_rad = 1e-6;        // stop when the steps shrink below these
  double min_step_trans_m = 1e-6;
  int max_evaluations = 20000;
  // Leave out pairs whose people touch the image border (truncated masks) while at least half
  // of the pairs remain: their off-image LiDAR points bias the result.
  bool exclude_truncated = true;
  // After each refinement, re-select the inliers among all pairs with Eq. (1) <= threshold_sample
  // and refine again until the set is stable; false refines once on Algorithm 2's inliers.
  bool reselect_inliers = true;
  // After the first refinement, refine again from the pose turned by +-1 .. +-ring_alias_turns
  // ring spacings about the camera's x axis and keep a clearly better one (ring_alias.hpp); 0: off.
  int ring_alias_turns = 2;
  // The sub-pixel loss reads distances from the person pixels' outline, this far beyond their
  // centres (LossConfig::outline_px): points on a person's outline then cost nothing at the true
  // pose, and the fit no longer shrinks the projected people. 0: from the centres.
  double outline_px = 0.5;
  // The sub-pixel loss also charges each LiDAR ring's two ends on a person how far along the row
  // they lie from their own person's outline, this much (LossConfig::ring_end_weight,
  // ring_ends.hpp); the ends are assigned to the people's regions at Algorithm 2's pose. 0: off.
  double ring_end_weight = 1.0;
  // Algorithm 1 runs at most this many generations before the refinement (never more than
  // EvolutionConfig::max_iterations, the paper's iter_max); 0: iter_max. In the default run the
  // evolution only has to land in the basin the refinement then searches; its last 200 of 400
  // generations took a third of a run and left the accuracy as it was over 82 synthetic drives
  // (docs/validation/accuracy.md). The paper mode (refine none) always runs iter_max.
  int evolution_generations = 200;
  // The shortened evolution's fit is kept only when, once refined, at least this share of all the
  // pairs lies within OutlierConfig::threshold_px of it (Algorithm 2's test, at a lower ratio);
  // else a fit after iter_max generations runs too. Measured shares at the refined fits: clean
  // synthetic drives 0.90-0.99, realistic noise 0.64-0.88, a drive whose short evolution ended in
  // a wrong basin 0.45 (docs/validation/accuracy.md). 0: never run again.
  double evolution_min_share = 0.5;
  static const ParameterRanges<RefineConfig>& ranges();  // checked by validate()
  void validate() const;
};

// Issue 21: the camera-LiDAR time offset delta (time_offset_s, INTERFACE.md): the image stamped t
// was captured at t + delta on the LiDAR's clock. Beyond the paper: the paper mode (refine none)
// never moves points in time, whatever the mode says.
enum class TimeOffsetMode : std::uint8_t { kEstimate, kFixed, kNone };
const char* toString(TimeOffsetMode mode);  // "estimate", "fixed", "none"

struct TimeOffsetConfig {
  TimeOffsetMode mode = TimeOffsetMode::kEstimate;
  double offset_s = 0.0;  // fixed: the known delta; estimate: where the search starts
  double max_s = 0.2;     // estimate: delta is searched within [-max_s, max_s]
  // The coarse search refines the pose at every step across the range before the joint
  // refinement: 10 ms is 2 cm of travel at 2 m/s, well inside the refinement's reach.
  double coarse_step_s = 0.01;
  double initial_step_s = 0.005;  // the joint refinement's first delta probe
  double min_step_s = 1e-5;       // and its smallest
  // Estimate only when the drive resolves delta to this (1 sigma, ms; timing_resolution.hpp):
  // on a drive that cannot tell a late camera from one mounted further forward, an estimated
  // delta trades centimetres of translation for nothing (the demo drive: 12 ms, 0.6 -> 4 cm).
  double max_resolution_ms = 5.0;
  // ...unless the data say the stamps are far off all the same: a joint refinement of pose and
  // delta from the pose-only fit that moves delta by at least twice the resolution and lowers
  // the loss by at least this fraction (end-of-scan stamps without per-point times, 110 ms off:
  // 57-84 %; steady drives that cannot tell, 0.3-5 %). 1 = never.
  double unresolved_min_gain = 0.25;
  // An estimate within this many resolutions (1 sigma) of offset_s is not told from it: the pose
  // fitted at offset_s and the offset itself are kept. On synchronised drives the joint fit's
  // seventh parameter otherwise costs accuracy for an offset of a millisecond or two (timing.md).
  // 0 = always the joint fit.
  double keep_start_sigmas = 2.0;
  static const ParameterRanges<TimeOffsetConfig>& ranges();  // checked by validate()
  void validate() const;
};

// Beyond the paper, after the local refinement (refine: local only; vertical_centring.hpp): the
// estimate is moved to the centre of the poses that keep every point within margin_px of its
// mask, in the plane of the image-vertical motions (rotation about the camera's x axis,
// translation along its y axis). Pairs that do not fit that well at the plane's best pose (a
// mask the segmentation eroded, a person half missed) are left out of the region; the stage is
// applied only when at least min_fitting_fraction of the pairs fit and those fit (mean Eq. 1 cost
// with the margin at the plane's best pose <= max_mean_cost_px).
struct VerticalCentringConfig {
  bool enabled = true;
  double margin_px = 1.0;          // sub-pixel distance that costs nothing: the pixel grid's own
  double max_mean_cost_px = 0.01;  // applied only when the points fit at least this well
  double pair_fit_px = 1e-4;       // a pair fits when its mean cost with the margin is <= this
                                   // at the plane's best pose (0: keep every pair)
  bool consensus_start = true;     // that best pose: where the most pairs fit (vertical_centring.hpp);
                                   // false: the minimum of the loss with the margin over all pairs
  double min_fitting_fraction = 0.25;  // applied only when at least this share of the pairs fit
  double tolerance = 0.02;         // region: loss <= best * (1 + tolerance) + 1e-5 px
  double outlying_fraction = 0.02; // region instead: at most this share of the fitting pairs
                                   // leave the margin (their cost above pair_fit_px); 0: none
                                   // may, the loss's level above
  int rays = 24;                   // directions sampled to trace the region's outline
  int iterations = 3;              // outline traced again from each new centre
  int resample_rays = 8;           // the bootstrap's resamples: fewer directions,
  int resample_bisections = 4;     // a coarser outline, traced once (centreResample)
  bool centre_roll = true;         // the region over the roll too (about camera z through the
                                   // camera); false: the plane's two only
  static const ParameterRanges<VerticalCentringConfig>& ranges();  // checked by validate()
  void validate() const;
};

struct CalibrationConfig {
  Algorithm algorithm = Algorithm::kOutlierRejection;
  EvolutionConfig evolution;
  OutlierConfig outlier;
  RefineConfig refine;
  TimeOffsetConfig time_offset;
  VerticalCentringConfig vertical_centring;  // used only with refine.mode = kLocal
  double behind_camera_penalty_c1 = 5.0;  // c1 of Eq. (2)
  std::uint64_t seed = 1;
  int num_threads = 0;  // 0 = all cores; results do not depend on it
  // The evolution as this run makes it: the paper's (refine none) runs max_iterations
  // generations; the default run at most refine.evolution_generations of them.
  EvolutionConfig evolutionRun() const;
  static const ParameterRanges<CalibrationConfig>& ranges();  // checked by validate()
  void validate() const;
};

}  // namespace thermal_lidar_calibration
