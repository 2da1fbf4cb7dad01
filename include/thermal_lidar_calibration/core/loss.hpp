#pragma once
// Equations (1)-(3) of the paper, evaluated fast for many candidates at once.

#include "thermal_lidar_calibration/core/calibration_pair.hpp"
#include "thermal_lidar_calibration/core/camera_model.hpp"
#include "thermal_lidar_calibration/core/distance_map.hpp"
#include "thermal_lidar_calibration/core/extrinsic.hpp"
#include "thermal_lidar_calibration/core/parameter_range.hpp"
#include "thermal_lidar_calibration/core/ring_ends.hpp"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

namespace thermal_lidar_calibration {

// How a projected point p (sub-pixel) reads the distance map.
enum class PixelRule : std::uint8_t {
  kNearest,   // the paper: round p to the nearest pixel, exact L1 to the nearest person pixel
  kBilinear,  // sub-pixel: continuous in p (used by the local refinement)
};

struct LossConfig {
  LossConfig() = default;
  LossConfig(double c1, PixelRule rule, std::optional<double> time_offset = std::nullopt)
      : behind_camera_penalty_c1(c1), pixel_rule(rule), time_offset_s(time_offset) {}
  double behind_camera_penalty_c1 = 5.0;  // c1 of Eq. 2: z <= 0 scores c1 * max(h, w)
  PixelRule pixel_rule = PixelRule::kNearest;
  // Issue 21: nullopt scores the points where they were captured (the paper; pairs without
  // measured motion always). A value delta moves each point with its person's motion to the
  // instant the image was captured, stamp + delta (person_timing.hpp).
  std::optional<double> time_offset_s;
  // Beyond the paper (0 = the paper): a point in front of the camera within this many pixels of
  // a mask costs nothing, psi' = max(0, psi - margin_px); the vertical centring's loss
  // (vertical_centring.hpp).
  double margin_px = 0.0;
  // Beyond the paper, the sub-pixel rule only: a mask marks the pixels whose centre a person
  // covers, and the distance map measures from those centres, so a point on a person's true
  // outline reads about half a pixel (the outline lies anywhere between the last person pixel's
  // centre and the next pixel's) and the loss's minimum pulls the outline points inward: the
  // projected people shrink, and the translation leaned forward on every drive (issue 24,
  // docs/validation/accuracy.md). The sub-pixel rule reads from the person pixels' outline instead,
  // half a pixel beyond their centres: psi' = max(0, psi - outline_px). A margin counts from the
  // centres as before; the larger of the two applies. 0 = distances from the centres.
  double outline_px = 0.5;
  // Beyond the paper, the sub-pixel rule only, on an evaluator whose ring ends were assigned
  // (LossEvaluator::withRingEnds, ring_ends.hpp): each pair's loss adds this times the mean over
  // its rings' ends of ringEndCost (how far each end lies from where it should against its own
  // person's outline, along the row), at most kRingEndCapPx each; a ring with both ends measured
  // costs ringPairCost, its width weighed kRingWidthWeight. 0 = off.
  double ring_end_weight = 0.0;
  static constexpr float kRingEndCapPx = 3.0f;
  static constexpr float kRingWidthWeight = 0.5f;
  static const ParameterRanges<LossConfig>& ranges();  // checked by validate()
  void validate() const;
};

// Points of one pair in float32 structure-of-arrays form plus its distance map. The arrays are
// zero-padded to a multiple of 8 so the vector kernels never copy a partial last block. With a
// time offset, x, y, z are the points at the image's instant (base + delta * velocity); the
// base and velocity arrays let another delta be applied without rebuilding the distance map.
struct PreparedPair {
  std::vector<float> x, y, z;  // padded; the first `count` entries are the points
  std::size_t count = 0;
  std::shared_ptr<const DistanceMap> distance;  // shared by the evaluators of other offsets
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // bounding sphere of the points
  double radius = 0.0;
  // With motion: the points at the image stamp (delta = 0) and their velocities, unpadded; null
  // without. Shared by the evaluators of other offsets, which only move x, y, z.
  // With the vehicle turning (CalibrationPair::turn_rate_rps) the velocity at delta = 0 is the
  // point's v + a T0 (T0 its lead time) and a = ax, ay the bend; without, ax and ay are empty.
  struct Motion {
    std::vector<float> base_x, base_y, base_z, vx, vy, vz, ax, ay;
  };
  std::shared_ptr<const Motion> motion;
  PreparedPair(const CalibrationPair& pair, std::optional<double> time_offset_s);
  void moveTo(double time_offset_s);  // x, y, z, centre, radius at another delta
 private:
  void bound();
};

class LossEvaluator {
 public:
  // Builds every pair's distance map once. Throws std::invalid_argument on an empty pair or a
  // mask whose size differs from the camera.
  LossEvaluator(const CameraModel& camera, const std::vector<CalibrationPair>& pairs,
                LossConfig config);
  ~LossEvaluator();
  LossEvaluator(LossEvaluator&&) noexcept;

  // The same pairs and distance maps read with another pixel rule (shares the prepared data).
  LossEvaluator withPixelRule(PixelRule rule) const;
  // The same pairs with their points moved to another camera time offset (shares the distance
  // maps; copies and moves the points). Throws std::logic_error without a time offset.
  LossEvaluator withTimeOffset(double time_offset_s) const;
  // An evaluator over `pairs` only (indices into this one, duplicates allowed): its pair k is
  // pair pairs[k] as prepared here, with its points, motion and ring ends. Each pair reads the
  // same, so a sum over local indices equals the sum over the pairs they stand for; a copy at
  // another time offset then moves only these. Throws std::invalid_argument on an index past
  // pairCount().
  LossEvaluator ofPairs(const std::vector<std::size_t>& pairs) const;
  // Whether some pair has measured motion (a time offset then moves points).
  bool hasMotion() const;
  // The same with another LossConfig::margin_px (shares the prepared data).
  LossEvaluator withMargin(double margin_px) const;
  // The same with another LossConfig::outline_px (shares the prepared data).
  LossEvaluator withOutline(double outline_px) const;
  // The same with the rings' ends of each pair's people assigned to their own mask regions where
  // the pose `at` projects them (assignRingEnds; `pairs` are the evaluator's, in its order), read
  // with LossConfig::ring_end_weight `weight`. Copies the points, shares the distance maps.
  // Throws std::invalid_argument when `pairs` are not the evaluator's.
  LossEvaluator withRingEnds(const std::vector<CalibrationPair>& pairs, const Extrinsic& at, double weight,
                             const RingEndRules& rules = {}) const;
  // The same with LossConfig::ring_end_weight 0 (shares the prepared data and the ends).
  LossEvaluator withoutRingEnds() const;
  // Ring ends assigned over all pairs (0 without withRingEnds).
  std::size_t ringEndCount() const;

  std::size_t pairCount() const;
  // True when pair i's people touch the image border: the mask shows only part of someone the
  // LiDAR cluster holds whole, so some of the pair's points have no counterpart in the mask.
  bool maskTouchesImageBorder(std::size_t pair) const;
  // Mean of the LiDAR points of the given pairs (all pairs when empty), in the LiDAR frame.
  Eigen::Vector3d centroid(const std::vector<std::size_t>& pairs) const;
  const CameraModel& camera() const { return camera_; }
  const LossConfig& config() const { return config_; }

  // Eq. (1): mean psi over the points of pair i.
  double pairLoss(std::size_t pair, const Extrinsic& extrinsic) const;
  // Eq. (3) over the given pairs (all pairs when `subset` is empty).
  double loss(const Extrinsic& extrinsic, const std::vector<std::size_t>& subset = {}) const;
  // Eq. (3) for many candidates; out[i] for candidates[i]. Parallel over candidates with
  // `threads` threads (0 = all cores); each candidate's sum runs in a fixed order, so the
  // numbers do not depend on the thread count.
  void lossBatch(const std::vector<Extrinsic>& candidates, const std::vector<std::size_t>& subset,
                 std::vector<double>& out, int threads) const;
  // For many candidates, how many of the given pairs (duplicates counted; all pairs when `subset`
  // is empty) have Eq. (1) above `level`: out[i] for candidates[i]. Parallel as lossBatch.
  void pairsAboveBatch(const std::vector<Extrinsic>& candidates, const std::vector<std::size_t>& subset,
                       double level, std::vector<double>& out, int threads) const;
  // Fraction of pair i's points in front of the camera that land inside the image.
  double insideFraction(std::size_t pair, const Extrinsic& extrinsic) const;
  // Algorithm 1's acceptance test for an initial individual: does some pair in `pairs` put at
  // least `fraction` of its points inside the image? Same answer as insideFraction() pair by
  // pair, but skips pairs whose bounding sphere is behind the camera and stops counting as soon
  // as the answer is known (most random poses look away from the people).
  bool somePairInside(const std::vector<std::size_t>& pairs, const Extrinsic& extrinsic,
                      double fraction) const;

  // Projected points (pair i, candidate) scored so far by this evaluator (for throughput stats).
  std::uint64_t pointsEvaluated() const;

 private:
  struct Impl;
  LossEvaluator(CameraModel camera, LossConfig config, std::shared_ptr<Impl> impl);
  // lossBatch's and pairsAboveBatch's loop: out[c] is the sum of term(Eq. (1)) over the subset's
  // pairs, in its order, for candidates[c]; returns how many pairs that is.
  template <typename Term>
  std::size_t sumOverPairs(const std::vector<Extrinsic>& candidates, const std::vector<std::size_t>& subset,
                           std::vector<double>& out, int threads, Term term) const;
  CameraModel camera_;
  LossConfig config_;
  std::shared_ptr<Impl> impl_;
};

}  // namespace thermal_lidar_calibration
