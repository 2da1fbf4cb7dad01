// The drift watch and the camera's time offset (issue 21): a camera whose latency changes
// mid-drive is a timing change, found with the offset alone (pose held) and kept apart from the
// extrinsic's state; a real turn of the camera is not explained by any offset; without a reference
// offset the watch behaves as before.
#include "thermal_lidar_calibration/core/drift_monitor.hpp"
#include "thermal_lidar_calibration/core/drift_timing.hpp"
#include "thermal_lidar_calibration/core/person_timing.hpp"

#include "../support/moving_pairs.hpp"
#include "thermal_lidar_calibration/synthetic/synthetic_rig.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace thermal_lidar_calibration;
using test_support::fieldsafeCamera;
using test_support::fieldsafeTruth;

namespace {

// `n` pairs seen with `truth` by a camera `delay_s` late, on a drive with stops, turns and walkers.
std::vector<CalibrationPair> drivePairs(const Extrinsic& truth, double delay_s, int n, std::uint64_t seed) {
  test_support::SyntheticPairsOptions o;
  o.pairs = n;
  o.seed = seed;
  o.min_range_m = 5.0;
  o.max_range_m = 16.0;
  auto pairs = test_support::makeSyntheticPairs(fieldsafeCamera(), truth, o);
  test_support::MotionOptions m;
  m.delay_s = delay_s;
  m.seed = seed + 1;
  test_support::addMotion(pairs, m);
  return pairs;
}

// One stream, restamped so the pairs follow each other (the image and the scan of a pair keep
// their common instant: the points were moved for it).
std::vector<CalibrationPair> stream(std::vector<CalibrationPair> a, const std::vector<CalibrationPair>& b) {
  a.insert(a.end(), b.begin(), b.end());
  for (std::size_t i = 0; i < a.size(); ++i) a[i].stamp_s = a[i].cloud_stamp_s = 100.0 + static_cast<double>(i);
  return a;
}

struct Watched {
  DriftState extrinsic = DriftState::kOk;
  DriftState timing = DriftState::kOk;
  std::optional<double> timing_change_s;
};

Watched watch(const std::vector<CalibrationPair>& pairs, std::optional<double> time_offset_s) {
  CalibrationConfig calibration;
  calibration.num_threads = 1;
  DriftMonitor m(fieldsafeCamera(), fieldsafeTruth(), DriftConfig{}, calibration, time_offset_s);
  Watched w;
  for (const CalibrationPair& p : pairs) {
    if (const auto r = m.addPair(p)) {
      w.extrinsic = std::max(w.extrinsic, r->state);
      w.timing = std::max(w.timing, r->timing_state);
      if (r->timing_change_s) w.timing_change_s = r->timing_change_s;
    }
  }
  return w;
}

}  // namespace

TEST(DriftTiming, RebasedPairsMoveByTheFurtherOffsetOnly) {
  const auto pairs = drivePairs(fieldsafeTruth(), 0.06, 3, 5);
  for (const CalibrationPair& p : pairs) {
    const CalibrationPair rebased = rebasedAtTimeOffset(p, 0.06);
    ASSERT_TRUE(hasMeasuredMotion(rebased));
    const auto direct = pointsAtImageTime(p, 0.08);
    const auto via_rebased = pointsAtImageTime(rebased, 0.02);
    ASSERT_EQ(direct.size(), via_rebased.size());
    for (std::size_t i = 0; i < direct.size(); ++i) EXPECT_LT((direct[i] - via_rebased[i]).norm(), 1e-5f);
  }
}

TEST(DriftTiming, ALatencyChangeIsFoundWithThePoseHeld) {
  // The reference offset is 60 ms; the camera now lags 100 ms: the window needs +40 ms.
  std::vector<CalibrationPair> window;
  for (const CalibrationPair& p : drivePairs(fieldsafeTruth(), 0.10, 30, 9)) {
    window.push_back(rebasedAtTimeOffset(p, 0.06));
  }
  const auto fit = fitTimingChange(fieldsafeCamera(), window, fieldsafeTruth(), fieldsafeTruth(), 0.2, 5.0, 5.0);
  ASSERT_TRUE(fit);
  EXPECT_EQ(fit->pairs_with_motion, 30u);
  EXPECT_NEAR(fit->change_s, 0.04, 0.003);
  EXPECT_LT(fit->loss, 0.2 * fit->loss_reference) << fit->loss << " vs " << fit->loss_reference;
}

TEST(DriftTiming, ATurnOfTheCameraIsNotExplainedByAnOffset) {
  const Extrinsic turned = synthetic::bumpedExtrinsic(fieldsafeTruth(), Eigen::Vector3d(0.3, -0.8, 0.5), 0.5,
                                                      Eigen::Vector3d::Zero());
  std::vector<CalibrationPair> window;
  for (const CalibrationPair& p : drivePairs(turned, 0.06, 30, 11)) window.push_back(rebasedAtTimeOffset(p, 0.06));
  // The window's own fit of the pose is the turned rig.
  const auto fit = fitTimingChange(fieldsafeCamera(), window, fieldsafeTruth(), turned, 0.2, 5.0, 5.0);
  ASSERT_TRUE(fit);
  EXPECT_LT(fit->explained(), 0.8) << "change " << fit->change_s;
}

TEST(DriftTiming, NoMotionNoTimingFit) {
  test_support::SyntheticPairsOptions o;
  o.pairs = 5;
  const auto pairs = test_support::makeSyntheticPairs(fieldsafeCamera(), fieldsafeTruth(), o);
  EXPECT_FALSE(fitTimingChange(fieldsafeCamera(), pairs, fieldsafeTruth(), fieldsafeTruth(), 0.2, 5.0, 5.0));
}

TEST(DriftTiming, TheWatchReportsALatencyChangeAsTimingNotDrift) {
  const auto pairs = stream(drivePairs(fieldsafeTruth(), 0.06, 40, 13), drivePairs(fieldsafeTruth(), 0.10, 40, 15));
  const Watched with_offset = watch(pairs, 0.06);
  EXPECT_EQ(with_offset.extrinsic, DriftState::kOk);
  EXPECT_NE(with_offset.timing, DriftState::kOk);
  ASSERT_TRUE(with_offset.timing_change_s);
  EXPECT_NEAR(*with_offset.timing_change_s, 0.04, 0.005);
  // Without the reference's offset the watch does not look at timing.
  EXPECT_EQ(watch(pairs, std::nullopt).timing, DriftState::kOk);
}

TEST(DriftTiming, AStableLatencyStaysOk) {
  const auto pairs = stream(drivePairs(fieldsafeTruth(), 0.06, 40, 13), drivePairs(fieldsafeTruth(), 0.06, 40, 15));
  const Watched w = watch(pairs, 0.06);
  EXPECT_EQ(w.extrinsic, DriftState::kOk);
  EXPECT_EQ(w.timing, DriftState::kOk);
  EXPECT_FALSE(w.timing_change_s);
}
