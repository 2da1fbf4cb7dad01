#pragma once
// How far to trust each axis of an estimate: 95 % intervals from a bootstrap over pairs.
// Each resample draws the pairs with replacement (in blocks of consecutive pairs when
// block_pairs > 1, because neighbouring pairs of a drive see the same people in nearly the same
// place), refines locally from the estimate with the sub-pixel loss, and records how far the
// refined pose moved, per camera axis (pose_difference.hpp). Resamples run in parallel; resample
// b draws from its own stream of the seed, so the result does not depend on the thread count.
//
// Callable on any subset of pairs from any estimate (a drift window, a quick check while
// collecting) with a cheaper setting: UncertaintyConfig::quick().

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "thermal_lidar_calibration/core/calibration_config.hpp"
#include "thermal_lidar_calibration/core/parameter_range.hpp"
#include "thermal_lidar_calibration/core/calibration_pair.hpp"
#include "thermal_lidar_calibration/core/camera_model.hpp"
#include "thermal_lidar_calibration/core/extrinsic.hpp"
#include "thermal_lidar_calibration/core/loss.hpp"

namespace thermal_lidar_calibration {

struct VerticalCentringOutcome;  // vertical_centring.hpp

using Vector6d = Eigen::Matrix<double, 6, 1>;

struct UncertaintyConfig {
  int resamples = 100;       // bootstrap resamples; >= 2 (the result file uses >= 50)
  // Consecutive pairs drawn together; 1 = the plain pair bootstrap. 5 by default: pairs a few
  // frames apart see the same people in nearly the same place, so their errors are not
  // independent, and single-pair resampling stated intervals too narrow (on 10 realistic
  // synthetic drives the 95 % interval held the truth along camera x 7 times with 1, 9 with 5).
  int block_pairs = 5;
  double confidence = 0.95;  // two-sided level of the intervals, (0, 1)
  std::uint64_t seed = 1;
  int num_threads = 0;  // 0 = all cores; the result does not depend on it
  // The local refinement of each resample (same search as RefineConfig, started at the estimate
  // with steps about the size of the expected deviations).
  double initial_step_rot_rad = 0.002;
  double initial_step_trans_m = 0.005;
  double min_step_rot_rad = 1e-5;
  double min_step_trans_m = 1e-5;
  int max_evaluations = 4000;  // per resample
  // With the time offset estimated (issue 21), each resample also refines it.
  double initial_step_time_s = 0.002;
  double min_step_time_s = 1e-5;
  // A cheaper setting for windows and checks while collecting: 30 resamples, coarser stop.
  static UncertaintyConfig quick();
  static const ParameterRanges<UncertaintyConfig>& ranges();  // checked by validate()
  void validate() const;  // throws std::invalid_argument naming the key and range
};

struct Uncertainty {
  // Half-widths of the intervals (estimate +- half-width) per camera axis.
  Eigen::Vector3d rotation_deg = Eigen::Vector3d::Zero();
  Eigen::Vector3d translation_cm = Eigen::Vector3d::Zero();
  // The percentile interval of the resampled deviations from the estimate (rotation deg first,
  // then translation cm): lower and upper ends, and their mean (the bootstrap's bias estimate).
  Vector6d lower = Vector6d::Zero(), upper = Vector6d::Zero(), mean = Vector6d::Zero();
  Vector6d std_dev = Vector6d::Zero();  // standard deviation of the resampled deviations
  std::vector<Vector6d> deviations;  // one per resample, in resample order
  int resamples = 0;                 // completed resamples
  int block_pairs = 1;
  double confidence = 0.95;
  std::size_t pairs = 0;          // pairs resampled
  std::uint64_t evaluations = 0;  // loss evaluations, all resamples
  // Issue 21: with the time offset estimated, each resample refined it too.
  bool timed = false;
  double time_offset_ms = 0.0;  // half-width, as rotation_deg / translation_cm
  double time_offset_lower_ms = 0.0, time_offset_upper_ms = 0.0, time_offset_std_ms = 0.0;
  std::vector<double> time_offset_deviations_ms;  // one per resample
  // Correlation of the resampled time offsets with the translations along camera x, y, z: near
  // +-1 where the drive cannot tell a late camera from one mounted further along its travel.
  Eigen::Vector3d time_translation_correlation = Eigen::Vector3d::Zero();
  // What each resample's fit read and did, as the estimate's: the rings' ends (ring_ends.hpp),
  // the vertical centring (vertical_centring.hpp).
  bool ring_ends = false;
  bool centred = false;
  double seconds = 0.0;
  bool stopped = false;        // the callback asked to stop; fewer resamples
  // "bootstrap over pairs in blocks of 5, 100 resamples, local refinement from the estimate",
  // then what the fits also did (the time offset, the rings' ends, the centring).
  std::string method() const;
  // Half-width of axis k, rotation axes 0-2 (deg), translation axes 3-5 (cm).
  double halfWidth(int k) const { return k < 3 ? rotation_deg[k] : translation_cm[k - 3]; }
};

// Called after each finished resample with the number finished; return false to stop (the
// resamples under way finish, the rest are skipped; intervals from those done, if >= 2).
using UncertaintyCallback = std::function<bool(int done, int total)>;

// `loss` supplies the pairs and camera (its pixel rule is replaced by the sub-pixel one);
// `pairs` are indices into it, in time order (duplicates allowed), at least 3.
// With `timing` (the time offset was estimated), `loss` must be at the estimated offset and each
// resample refines the offset too, within timing->max_s. With `centring` (the estimate's vertical
// centring), each resample's refined pose is centred as the estimate was (centreResample in
// vertical_centring.hpp), with its points at the resample's own offset, so that the intervals
// describe the estimator that made the estimate.
// Throws std::invalid_argument on a bad config or too few pairs.
Uncertainty estimateUncertainty(const LossEvaluator& loss, const Extrinsic& estimate,
                                const std::vector<std::size_t>& pairs,
                                const UncertaintyConfig& config,
                                const UncertaintyCallback& callback = {},
                                const std::optional<TimeOffsetConfig>& timing = std::nullopt,
                                const VerticalCentringOutcome* centring = nullptr);
// Resample `index` of a bootstrap with `seed`: pairs.size() entries of `pairs` drawn with
// replacement, in runs of `block_pairs` consecutive entries (the last run cut short).
std::vector<std::size_t> resamplePairs(const std::vector<std::size_t>& pairs, int block_pairs,
                                       std::uint64_t seed, int index);

// The same for a plain list of pairs (all used), building the evaluator.
Uncertainty estimateUncertainty(const CameraModel& camera,
                                const std::vector<CalibrationPair>& pairs,
                                const Extrinsic& estimate, const UncertaintyConfig& config,
                                double behind_camera_penalty_c1 = 5.0);

}  // namespace thermal_lidar_calibration
