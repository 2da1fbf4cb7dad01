// The core parameter table: every key calibration_node and calibrate_bag share.
//
// Adding a key:
//   1. give its struct a field whose member initialiser is the default (the core config
//      structs in core/, or CoreParameters in app/parameters/core_parameters.hpp);
//   2. add one row below, in the section it belongs to:
//        <group>.integer / real / boolean / text / choice / integerChoice(
//            "key", &Struct::field, allowed values, [unit,] "what it is", ["note"]);
//      a number the core checks has its range in its struct's ranges() (core/parameter_range.hpp),
//      and its row says kConfigRange;
//   3. run scripts/update_parameter_docs.sh: it rewrites config/default.yaml and README's
//      parameter table from the rows (test_parameter_docs fails until they agree).
// A new config struct gets one group line (`auto x = t.group<XConfig>(...)`) and, if it has
// rules across keys, a validate() called from finishLoading() below. Keys of one part only (the
// node's) go in that part's own table with the same machinery (src/app/parameters/node_parameter_table.cpp).

#include "thermal_lidar_calibration/app/parameters/core_parameters.hpp"

#include "thermal_lidar_calibration/app/parameters/association_parameters.hpp"
#include "thermal_lidar_calibration/app/parameters/point_time_field.hpp"
#include "thermal_lidar_calibration/core/loss.hpp"

#include <limits>

namespace thermal_lidar_calibration {
namespace {

// Issue 8: how far to trust a result. The verdict's thresholds are the user's to set.
void addQualityRows(ParameterTable<CoreParameters>& t) {
  auto quality = t.group<QualityConfig>([](CoreParameters& p) -> QualityConfig& { return p.quality; });
  auto uncertainty = t.group<UncertaintyConfig>(
      [](CoreParameters& p) -> UncertaintyConfig& { return p.quality.uncertainty; });
  auto coverage = t.group<CoverageConfig>([](CoreParameters& p) -> CoverageConfig& { return p.quality.coverage; });
  auto verdict = t.group<VerdictConfig>([](CoreParameters& p) -> VerdictConfig& { return p.quality.verdict; });
  t.section("Quality: uncertainty, coverage, verdict (beyond the paper; issue #8)");
  quality.boolean("uncertainty", &QualityConfig::uncertainty_enabled,
                  "95 % intervals per axis by a bootstrap over the pairs used, after the fit");
  // Narrower than the library's [2, 100000] (the drift update draws fewer): a calibration's
  // intervals from fewer than 50 resamples are too rough to judge it by.
  uncertainty.integer("uncertainty_resamples", &UncertaintyConfig::resamples, {50, 100000}, "",
                      "bootstrap resamples (each a local refinement from the result; parallel, "
                      "deterministic per seed)");
  uncertainty.integer("uncertainty_block_pairs", &UncertaintyConfig::block_pairs, kConfigRange, "",
                      "pairs drawn together in runs of consecutive pairs (moving-block bootstrap: "
                      "neighbouring pairs of a drive see the same people in nearly the same place); 1 = single pairs");
  coverage.real("coverage_near_far_split_m", &CoverageConfig::near_far_split_m, aboveRange(0, 1000), "m",
                "a person nearer than this (LiDAR range) counts as near");
  verdict.real("quality_good_rotation_deg", &VerdictConfig::good_rotation_deg, kConfigRange, "deg",
               "good: every rotation half-width at most this");
  verdict.real("quality_good_translation_cm", &VerdictConfig::good_translation_cm, kConfigRange, "cm",
               "good: every translation half-width at most this");
  verdict.real("quality_usable_rotation_deg", &VerdictConfig::usable_rotation_deg, kConfigRange, "deg",
               "usable: every rotation half-width at most this", "at least quality_good_rotation_deg");
  verdict.real("quality_usable_translation_cm", &VerdictConfig::usable_translation_cm, kConfigRange,
               "cm", "usable: every translation half-width at most this", "at least quality_good_translation_cm");
  verdict.integer("quality_good_pairs", &VerdictConfig::good_pairs, kConfigRange, "", "good: at least this many pairs used");
  verdict.integer("quality_usable_pairs", &VerdictConfig::usable_pairs, kConfigRange, "",
                  "usable: at least this many pairs used", "at most quality_good_pairs");
  verdict.real("quality_good_third_fraction", &VerdictConfig::good_third_fraction, kConfigRange, "",
               "good: each horizontal third of the image holds at least this fraction of the person pixels");
  verdict.real("quality_usable_third_fraction", &VerdictConfig::usable_third_fraction, kConfigRange, "",
               "usable: each third at least this fraction (below: collect more, naming the third)",
               "at most quality_good_third_fraction");
  verdict.integer("quality_min_people_near", &VerdictConfig::min_people_near, kConfigRange, "",
                  "people nearer than coverage_near_far_split_m needed for good");
  verdict.integer("quality_min_people_far", &VerdictConfig::min_people_far, kConfigRange, "",
                  "people at or beyond coverage_near_far_split_m needed for good");
  verdict.integer("quality_good_distinct_positions", &VerdictConfig::good_distinct_positions, kConfigRange, "",
                  "good: people stood in at least this many distinct places");
  verdict.integer("quality_usable_distinct_positions", &VerdictConfig::usable_distinct_positions, kConfigRange,
                  "", "usable: at least this many distinct places", "at most quality_good_distinct_positions");
  verdict.real("quality_max_loss_px", &VerdictConfig::max_loss_px, kConfigRange, "px",
               "collect_more when the fit's loss on the pairs it used is above this (typical fits 0.03-0.2 px; "
               "fits carried by mismatched pairs 2-25 px)");
}

// Issue 21: the camera's time offset against the LiDAR, and the people's motion that measures it.
void addTimingRows(ParameterTable<CoreParameters>& t) {
  auto timing = t.group<TimeOffsetConfig>(
      [](CoreParameters& p) -> TimeOffsetConfig& { return p.calibration.time_offset; });
  auto motion = t.group<MotionConfig>([](CoreParameters& p) -> MotionConfig& { return p.motion; });
  auto verdict = t.group<VerdictConfig>([](CoreParameters& p) -> VerdictConfig& { return p.quality.verdict; });
  auto top = t.fields();
  t.section("Sensor timing (beyond the paper; issue #21)");
  timing.choice("time_offset_mode", &TimeOffsetConfig::mode,
                {{"estimate", TimeOffsetMode::kEstimate}, {"fixed", TimeOffsetMode::kFixed}, {"none", TimeOffsetMode::kNone}},
                "must be 'estimate', 'fixed' or 'none'",
                "the image stamped t was captured at t + time_offset_s on the LiDAR's clock: estimate it with "
                "the extrinsic, use time_offset_s as known, or ignore timing (refine: none always ignores it)");
  timing.real("time_offset_s", &TimeOffsetConfig::offset_s, kConfigRange, "s",
              "fixed: the known offset; estimate: where the search starts (positive: the image shows the world "
              "after its stamp)");
  timing.real("time_offset_max_s", &TimeOffsetConfig::max_s, kConfigRange, "s",
              "estimate: the offset is searched within +- this", "at least |time_offset_s|");
  timing.real("time_offset_coarse_step_s", &TimeOffsetConfig::coarse_step_s, kConfigRange, "s",
              "grid step of the coarse search before the joint refinement", "at most time_offset_max_s");
  timing.real("time_offset_max_resolution_ms", &TimeOffsetConfig::max_resolution_ms, kConfigRange, "ms",
              "estimate only when the drive's motion resolves the offset to this (1 sigma, with the pose free); "
              "else it stays at time_offset_s and the verdict says why (straight steady driving resolves nothing)");
  timing.real("time_offset_unresolved_min_gain", &TimeOffsetConfig::unresolved_min_gain, kConfigRange, "",
              "estimate all the same when a joint refinement from the pose-only fit moves the offset by twice the "
              "resolution and lowers the loss by this fraction (the stamps are far off; 1 = never)");
  timing.real("time_offset_keep_start_sigmas", &TimeOffsetConfig::keep_start_sigmas, kConfigRange, "",
              "estimate: an offset found within this many resolutions (1 sigma) of time_offset_s is not told from it: "
              "the pose fitted at time_offset_s is kept and the offset stays there (a synchronised rig does not pay "
              "for the seventh parameter); 0 = always the joint fit");
  top.text("point_time_field", &CoreParameters::point_time_field,
           TextRule::required("must be auto, none or the name of a PointCloud2 field"),
           "the clusters' per-point capture time: auto (the first of time, t, timestamp, offset_time the "
           "cloud has; none of them: no per-point times), none (ignore them) or a field name; float32/64 "
           "seconds, relative to the header stamp or absolute, or (u)int32 nanoseconds relative to it");
  motion.integer("motion_window_scans", &MotionConfig::window_scans, {1, 10}, "",
                 "scans before and after a kept pair from which each person's velocity is fitted (a kept pair "
                 "waits for the later ones)");
  motion.real("motion_max_speed_mps", &MotionConfig::max_speed_mps, aboveRange(0, 100), "m/s",
              "fastest motion of a person relative to the LiDAR searched for in the next scan (vehicle and "
              "walk together)");
  motion.real("motion_max_gap_s", &MotionConfig::max_gap_s, aboveRange(0, 5), "s",
              "scans further apart than this do not continue a person's track");
  verdict.real("quality_good_time_offset_ms", &VerdictConfig::good_time_offset_ms, kConfigRange, "ms",
               "good: the estimated offset's 95 % half-width at most this");
  verdict.real("quality_usable_time_offset_ms", &VerdictConfig::usable_time_offset_ms, kConfigRange, "ms",
               "usable: at most this (and the drive's resolution too)", "at least quality_good_time_offset_ms");
  verdict.real("quality_good_time_resolution_ms", &VerdictConfig::good_time_resolution_ms, kConfigRange,
               "ms",
               "good: the drive's motion resolves the offset to this with the pose free (1 sigma; straight "
               "steady driving past standing people resolves nothing)");
  verdict.real("quality_timing_probe_ms", &VerdictConfig::timing_probe_ms, kConfigRange, "ms",
               "offset not estimated: a joint refinement from the fit that moves it this far and lowers the loss "
               "by quality_timing_min_gain names timing in the verdict");
  verdict.real("quality_timing_min_gain", &VerdictConfig::timing_min_gain, kConfigRange, "",
               "the loss reduction (fraction) that goes with quality_timing_probe_ms");
}

// Issue 9: the drift watch's window and what counts as a change (core/drift_config.hpp says why
// each default is what it is).
void addDriftRows(ParameterTable<CoreParameters>& t) {
  auto drift = t.group<DriftConfig>([](CoreParameters& p) -> DriftConfig& { return p.drift; });
  t.section("Drift watch (beyond the paper; issue #9)");
  drift.integer("monitor_window_pairs", &DriftConfig::window_pairs, kConfigRange, "",
                "the latest kept pairs a drift test looks at");
  drift.integer("monitor_period_pairs", &DriftConfig::period_pairs, kConfigRange, "",
                "a drift test after this many new kept pairs", "at most monitor_window_pairs");
  drift.integer("monitor_confirm_windows", &DriftConfig::confirm_windows, kConfigRange, "",
                "consecutive changed tests that confirm a change (ERROR); one is WARN");
  drift.real("monitor_significance", &DriftConfig::significance, kConfigRange, "",
             "a window's fit must beat the reference on held-out pairs with a signed-rank p-value below this "
             "(the offset test's two-sided p-values too)");
  drift.real("monitor_min_loss_ratio", &DriftConfig::min_loss_ratio, kConfigRange, "",
             "and the reference's loss on the window must be this many times the fit's");
  drift.real("monitor_min_rotation_deg", &DriftConfig::min_rotation_deg, kConfigRange, "deg",
             "and the change at least this large (or the translation's)");
  drift.real("monitor_min_translation_cm", &DriftConfig::min_translation_cm, kConfigRange, "cm",
             "translation change that counts (0 and 0: any size)");
  drift.real("monitor_min_offset_x_px", &DriftConfig::min_offset_x_px, kConfigRange, "px",
             "or: the people's image offsets against the reference differ from zero across the image "
             "(two-sided signed-rank p below monitor_significance) by at least this (above 12: off)");
  drift.real("monitor_min_offset_y_px", &DriftConfig::min_offset_y_px, kConfigRange, "px",
             "the same down the image (above 12: off)");
  drift.integer("monitor_folds", &DriftConfig::folds, kConfigRange, "",
                "cross-fitting folds of the held-out test", "at most monitor_window_pairs / 3");
  drift.integer("monitor_update_pairs", &DriftConfig::update_pairs, kConfigRange, "",
                "count-rule pairs since a confirmed change the new extrinsic is fitted on before it is final (with the association pairs among them)");
  drift.real("monitor_update_full_significance", &DriftConfig::update_full_significance,
             kConfigRange, "",
             "the new extrinsic is the better of a turn about the camera centre and a shift, unless the "
             "full pose predicts held-out pairs better with a signed-rank p-value below this (1: always "
             "the full pose)");
  drift.integer("monitor_update_uncertainty_resamples", &DriftConfig::update_uncertainty_resamples,
                kConfigRange, "",
                "the new extrinsic's 95 % intervals per axis: block-bootstrap resamples over its pairs, each a "
                "6-DOF refinement from it (0: none; else at least 2)");
  drift.integer("monitor_fit_max_evaluations", &DriftConfig::fit_max_evaluations, kConfigRange, "",
                "loss evaluations per refinement of a drift fit");
  drift.real("monitor_max_update_rotation_deg", &DriftConfig::max_update_rotation_deg,
             kConfigRange, "deg",
             "a new extrinsic turned further than this from the reference is never offered (calibrate again)");
  drift.real("monitor_max_update_translation_cm", &DriftConfig::max_update_translation_cm,
             kConfigRange, "cm", "nor one moved further than this");
  drift.real("monitor_min_timing_change_ms", &DriftConfig::min_timing_change_ms, kConfigRange, "ms",
             "a window the reference fits again with the camera's time offset moved by at least this, "
             "pose held, is a timing change, not a drift (needs the result's time offset; the fit must "
             "lower the loss by monitor_min_loss_ratio)");
  drift.real("monitor_timing_explained_fraction", &DriftConfig::timing_explained_fraction,
             kConfigRange, "",
             "a window the pose test calls changed is timing only if the offset alone explains this share of "
             "what the window's own pose fit gains");
}

// Table 1's Algorithms 1 and 2, and the local refinement after them.
void addOptimizerRows(ParameterTable<CoreParameters>& t) {
  auto calibration = t.group<CalibrationConfig>(
      [](CoreParameters& p) -> CalibrationConfig& { return p.calibration; });
  auto evolution = t.group<EvolutionConfig>(
      [](CoreParameters& p) -> EvolutionConfig& { return p.calibration.evolution; });
  auto outlier = t.group<OutlierConfig>(
      [](CoreParameters& p) -> OutlierConfig& { return p.calibration.outlier; });
  auto refine = t.group<RefineConfig>(
      [](CoreParameters& p) -> RefineConfig& { return p.calibration.refine; });
  t.section("Algorithm 1: evolutionary search (Table 1)");
  evolution.integer("population_size", &EvolutionConfig::population_size, kConfigRange, "",
                    "N_pop, individuals per generation");
  evolution.integer("max_iterations", &EvolutionConfig::max_iterations, kConfigRange, "",
                    "iter_max, generations");
  evolution.real("rotation_interval_rad", &EvolutionConfig::rotation_interval_rad,
                 kConfigRange, "rad", "initial rotation vector components ~ U(-a, a)");
  evolution.real("translation_interval_m", &EvolutionConfig::translation_interval_m,
                 kConfigRange, "m", "initial translation components ~ U(-a, a)");
  evolution.real("elite_fraction", &EvolutionConfig::elite_fraction, kConfigRange, "",
                 "pct_elite, fraction copied unchanged", "elite_fraction + crossover_fraction <= 1");
  evolution.real("crossover_fraction", &EvolutionConfig::crossover_fraction, kConfigRange,
                 "", "pct_crossover, fraction made by crossover");
  evolution.integer("initial_population_factor", &EvolutionConfig::initial_population_factor,
                    kConfigRange, "", "c2: first generation has c2 * N_pop individuals");
  evolution.real("sigma_rot_rad", &EvolutionConfig::sigma_rot_rad, kConfigRange, "rad",
                 "mutation noise U(-s, s) per rotation component");
  evolution.real("sigma_trans_m", &EvolutionConfig::sigma_trans_m, kConfigRange, "m",
                 "mutation noise U(-s, s) per translation component");
  evolution.real("min_inside_fraction", &EvolutionConfig::min_inside_fraction, kConfigRange,
                 "", "initial individual kept if some pair projects >= this fraction inside the image");
  // The loss owns this key's range; the calibration config only carries the value to it.
  const RealRange penalty_range =
      LossConfig::ranges().of("behind_camera_penalty_c1", &LossConfig::behind_camera_penalty_c1);
  calibration.real("behind_camera_penalty_c1", &CalibrationConfig::behind_camera_penalty_c1, penalty_range, "",
                   "c1 of Eq. (2): a point behind the camera scores c1 * max(h, w) px");

  t.section("Algorithm 2: outlier rejection (Table 1)");
  outlier.integer("min_sample_large", &OutlierConfig::min_sample_large, kConfigRange, "",
                  "min_sample when the dataset has >= min_sample_switch pairs");
  outlier.integer("min_sample_small", &OutlierConfig::min_sample_small, kConfigRange, "",
                  "min_sample otherwise");
  outlier.integer("min_sample_switch", &OutlierConfig::min_sample_switch, kConfigRange, "",
                  "dataset size at which min_sample_large is used");
  outlier.integer("outlier_iterations", &OutlierConfig::iterations, kConfigRange, "",
                  "iter_outlier, fitting attempts on random subsets");
  outlier.real("ratio_solution", &OutlierConfig::ratio_solution, kConfigRange, "",
               "a subset fit is accepted if this fraction of the other pairs is within threshold");
  outlier.real("threshold_sample_px", &OutlierConfig::threshold_px, kConfigRange, "px",
               "threshold_sample: a pair with Eq. (1) loss above this is an outlier",
               "MS2 rig: 1.5");

  t.section("Local refinement (beyond the paper; refine: local)");
  refine.real("refine_initial_step_rot_rad", &RefineConfig::initial_step_rot_rad,
              kConfigRange, "rad", "first probe step");
  refine.real("refine_initial_step_trans_m", &RefineConfig::initial_step_trans_m,
              kConfigRange, "m", "first probe step");
  refine.real("refine_min_step_rot_rad", &RefineConfig::min_step_rot_rad, kConfigRange, "rad",
              "stop when steps shrink below this", "<= refine_initial_step_rot_rad");
  refine.real("refine_min_step_trans_m", &RefineConfig::min_step_trans_m, kConfigRange, "m",
              "stop when steps shrink below this", "<= refine_initial_step_trans_m");
  refine.integer("refine_max_evaluations", &RefineConfig::max_evaluations, kConfigRange, "",
                 "loss evaluations at most");
  refine.boolean("refine_exclude_truncated", &RefineConfig::exclude_truncated,
                 "refine without pairs whose people touch the image border (while >= half the "
                 "pairs remain)");
  refine.boolean("refine_reselect_inliers", &RefineConfig::reselect_inliers,
                 "after refining, re-select inliers among all pairs (Eq. 1 <= threshold_sample_px) "
                 "and refine again until stable");
  refine.integer("refine_ring_alias_turns", &RefineConfig::ring_alias_turns, kConfigRange, "",
                 "after the first refinement, refine again from the pose turned by up to this many LiDAR ring "
                 "spacings up and down the image, and keep one whose loss is clearly lower (a fit one ring off "
                 "the truth is a local minimum); 0: off");
  refine.real("refine_outline_px", &RefineConfig::outline_px, kConfigRange, "px",
              "the refinement's sub-pixel loss measures a point's distance from the person pixels' outline, this "
              "far beyond their centres (a mask marks the pixels whose centre a person covers, so a point on a "
              "person's outline lies about half a pixel from the nearest one); 0: from the centres");
  refine.real("refine_ring_end_weight", &RefineConfig::ring_end_weight, kConfigRange, "",
              "the refinement's sub-pixel loss also charges each LiDAR ring's first and last point on a person "
              "how far along the image row it lies from where it should, half a point spacing inside that "
              "person's own mask region (a mask loss alone is lowest where the projected people are smaller; a "
              "ring with both ends measured is charged its middle and, weighed half, its width), this much per "
              "pair; 0: off");
  refine.integer("refine_evolution_generations", &RefineConfig::evolution_generations, kConfigRange, "",
                 "with refine local, Algorithm 1 runs at most this many generations (and never more than "
                 "max_iterations): the evolution only has to find the basin the refinement then searches; 0: "
                 "max_iterations, as the paper; refine none always runs max_iterations");
  refine.real("refine_evolution_min_share", &RefineConfig::evolution_min_share, kConfigRange, "",
              "the shortened evolution's fit is kept when, once refined, at least this share of all the pairs "
              "lies within threshold_sample_px of it; else a fit after max_iterations generations runs too and "
              "the fit with the larger share is kept (a short evolution can end in a wrong basin); 0: never");
}

}  // namespace

template <>
ParameterTable<CoreParameters> makeParameterTable() {
  ParameterTable<CoreParameters> t;
  auto top = t.fields();
  auto calibration = t.group<CalibrationConfig>(
      [](CoreParameters& p) -> CalibrationConfig& { return p.calibration; });
  auto refine = t.group<RefineConfig>(
      [](CoreParameters& p) -> RefineConfig& { return p.calibration.refine; });
  auto gate = t.group<GateConfig>([](CoreParameters& p) -> GateConfig& { return p.gate; });

  t.section("Algorithm and run control");
  calibration.integerChoice(
      "algorithm", &CalibrationConfig::algorithm,
      {{1, Algorithm::kPlain}, {2, Algorithm::kOutlierRejection}},
      "must be 1 (plain evolution) or 2 (with outlier rejection)",
      "1 = Algorithm 1 (evolution only), 2 = Algorithm 2 (outlier rejection)");
  refine.choice("refine", &RefineConfig::mode,
                {{"none", RefineMode::kNone}, {"local", RefineMode::kLocal}},
                "must be 'none' or 'local'", "local derivative-free refinement after the evolution");
  calibration.integer("seed", &CalibrationConfig::seed, {0, std::numeric_limits<long long>::max()},
                      "", "random seed: same seed + same data = same result");
  calibration.integer("num_threads", &CalibrationConfig::num_threads, kConfigRange, "",
                      "loss threads, 0 = all cores (the result does not depend on it)");

  addOptimizerRows(t);

  t.section("Frame gating and pairing (Section 3.1)");
  gate.integer("max_people", &GateConfig::max_people, {1, 1000}, "",
               "H_max: keep a frame only if both modalities count 1..H_max people");
  gate.integer("skip_frames", &GateConfig::skip_frames, {0, 100000}, "",
               "candidate frames ignored after a kept one");
  gate.integer("min_points_per_cluster", &GateConfig::min_points_per_cluster, {1, 1000000}, "",
               "a person cluster with fewer LiDAR points rejects the frame");
  top.real("sync_slop", &CoreParameters::sync_slop_s, aboveRange(0, 10), "s",
           "ApproximateTime max interval between image, mask and clusters");
  top.integer("sync_queue_size", &CoreParameters::sync_queue_size, {2, 10000}, "messages",
              "ApproximateTime queue per topic");
  top.integer("pairs_required", &CoreParameters::pairs_required, {1, 100000}, "",
              "node: pairs to collect before optimizing",
              "calibrate_bag uses every pair in the bag");
  addAssociationRows(t);
  addQualityRows(t);
  addTimingRows(t);
  addDriftRows(t);
  return t;
}

template <>
void finishLoading(const ParameterSource& source, CoreParameters& p) {
  // Cross-key rules (elite + crossover <= 1, min steps below initial steps, ...) are the core's.
  p.calibration.validate();
  p.gate.validate();
  p.quality.validate();
  p.motion.validate();
  p.drift.validate();
  p.pairing.validate();
  try {
    PointTimeField::parse(p.point_time_field);
  } catch (const std::invalid_argument& e) {
    throwBadParameter(source, "point_time_field", e.what());
  }
}

}  // namespace thermal_lidar_calibration
