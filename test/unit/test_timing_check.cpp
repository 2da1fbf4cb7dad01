// Whether a drive can tell the camera's time offset, and whether the residuals say the stamps
// are off (issue 21): a varied drive resolves it, a steady one cannot and the verdict says so in
// terms of timing; an offset left out shows as residuals that a joint refinement removes.

#include "thermal_lidar_calibration/core/timing_check.hpp"

#include "thermal_lidar_calibration/core/loss.hpp"
#include "thermal_lidar_calibration/core/verdict.hpp"

#include "../support/moving_pairs.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace thermal_lidar_calibration;
using test_support::fieldsafeCamera;
using test_support::fieldsafeTruth;

namespace {

std::vector<CalibrationPair> drive(double delay_s, bool steady) {
  test_support::SyntheticPairsOptions o;
  o.pairs = 30;
  o.seed = 17;
  o.min_range_m = 5.0;
  o.max_range_m = 16.0;
  auto pairs = test_support::makeSyntheticPairs(fieldsafeCamera(), fieldsafeTruth(), o);
  test_support::MotionOptions m;
  m.delay_s = delay_s;
  m.steady = steady;
  test_support::addMotion(pairs, m);
  return pairs;
}

// A fit at the truth's pose with the given offset and mode, every pair used.
CalibrationResult fitAt(const std::vector<CalibrationPair>& pairs, double offset_s, TimeOffsetMode mode) {
  CalibrationResult r;
  r.extrinsic = fieldsafeTruth();
  r.time_offset_s = offset_s;
  r.time_offset_mode = mode;
  r.time_offset_asked = mode;
  r.inliers.assign(pairs.size(), true);
  const LossEvaluator nearest(fieldsafeCamera(), pairs,
                              LossConfig{5.0, PixelRule::kNearest,
                                         mode == TimeOffsetMode::kNone ? std::nullopt : std::optional<double>(offset_s)});
  for (std::size_t i = 0; i < pairs.size(); ++i) r.pair_losses.push_back(nearest.pairLoss(i, r.extrinsic));
  r.loss = nearest.loss(r.extrinsic);
  return r;
}

bool mentions(const VerdictReport& v, const std::string& text) {
  for (const auto& r : v.reasons) {
    if (r.find(text) != std::string::npos) return true;
  }
  return false;
}

}  // namespace

TEST(TimingCheck, AVariedDriveResolvesTheOffsetAndASteadyOneCannot) {
  const auto varied = drive(0.06, false);
  const auto t = assessTiming(fieldsafeCamera(), varied, fitAt(varied, 0.06, TimeOffsetMode::kEstimate), std::nullopt,
                              TimeOffsetConfig{}, 5.0);
  ASSERT_TRUE(t);
  EXPECT_EQ(t->pairs_with_motion, varied.size());
  EXPECT_LT(t->resolution_ms, 3.0);
  EXPECT_GT(t->mean_image_speed_px_s, 10.0);
  EXPECT_FALSE(t->probe_offset_s) << "no probe when the offset was estimated";

  const auto steady = drive(0.06, true);
  const auto s = assessTiming(fieldsafeCamera(), steady, fitAt(steady, 0.06, TimeOffsetMode::kEstimate), std::nullopt,
                              TimeOffsetConfig{}, 5.0);
  ASSERT_TRUE(s);
  EXPECT_GT(s->resolution_ms, 100.0);  // every point moves alike: a translation mimics it all

  // The verdict: never good on the steady drive, and the reason is timing with what to do.
  Coverage coverage;  // coverage findings are not what is tested here
  const VerdictReport v = judgeQuality(coverage, std::nullopt, VerdictConfig{}, 0.1, s);
  EXPECT_EQ(v.verdict, Verdict::kCollectMore);
  ASSERT_FALSE(v.reasons.empty());
  EXPECT_EQ(v.reasons.front().rfind("timing", 0), 0u) << v.reasons.front();
  EXPECT_TRUE(mentions(v, "vary the speed"));
  EXPECT_FALSE(mentions(judgeQuality(coverage, std::nullopt, VerdictConfig{}, 0.1, t), "timing"));

  // Asked to estimate but left at its start (the fit found the drive could not resolve it): the
  // verdict says it was not estimated, and why.
  CalibrationResult kept = fitAt(steady, 0.0, TimeOffsetMode::kFixed);
  kept.time_offset_asked = TimeOffsetMode::kEstimate;
  const auto k = assessTiming(fieldsafeCamera(), steady, kept, std::nullopt, TimeOffsetConfig{}, 5.0);
  ASSERT_TRUE(k);
  const VerdictReport kv = judgeQuality(coverage, std::nullopt, VerdictConfig{}, 0.1, k);
  EXPECT_NE(kv.verdict, Verdict::kGood);
  EXPECT_TRUE(mentions(kv, "not estimated")) << kv.reasons.front();
}

TEST(TimingCheck, AnOffsetLeftOutIsNamedAndASynchronisedDriveIsNot) {
  const auto late = drive(0.06, false);
  const auto t = assessTiming(fieldsafeCamera(), late, fitAt(late, 0.0, TimeOffsetMode::kNone), std::nullopt,
                              TimeOffsetConfig{}, 5.0);
  ASSERT_TRUE(t);
  ASSERT_TRUE(t->probe_offset_s);
  EXPECT_NEAR(*t->probe_offset_s, 0.06, 0.005);
  EXPECT_LT(t->probe_loss, 0.5 * t->fit_loss);
  Coverage coverage;
  const VerdictReport v = judgeQuality(coverage, std::nullopt, VerdictConfig{}, 0.1, t);
  EXPECT_EQ(v.verdict, Verdict::kCollectMore);
  EXPECT_EQ(v.reasons.front().rfind("timing: the residuals follow", 0), 0u) << v.reasons.front();

  const auto synchronised = drive(0.0, false);
  const auto s = assessTiming(fieldsafeCamera(), synchronised, fitAt(synchronised, 0.0, TimeOffsetMode::kNone),
                              std::nullopt, TimeOffsetConfig{}, 5.0);
  ASSERT_TRUE(s && s->probe_offset_s);
  EXPECT_LT(std::abs(*s->probe_offset_s), 0.005);
  EXPECT_FALSE(mentions(judgeQuality(coverage, std::nullopt, VerdictConfig{}, 0.1, s), "timing"));
}

TEST(TimingCheck, PairsWithoutMotionHaveNothingToJudge) {
  auto pairs = drive(0.0, false);
  for (auto& p : pairs) p.point_velocity.clear();
  EXPECT_FALSE(assessTiming(fieldsafeCamera(), pairs, fitAt(pairs, 0.0, TimeOffsetMode::kNone), std::nullopt,
                            TimeOffsetConfig{}, 5.0));
}

TEST(TimingCheck, RankCorrelation) {
  EXPECT_DOUBLE_EQ(rankCorrelation({1, 2, 3, 4}, {10, 20, 30, 40}), 1.0);
  EXPECT_DOUBLE_EQ(rankCorrelation({1, 2, 3, 4}, {4, 3, 2, 1}), -1.0);
  EXPECT_DOUBLE_EQ(rankCorrelation({1, 2, 3, 4}, {1, 100, 2, 3}), 0.4);  // ranks, not values
  EXPECT_DOUBLE_EQ(rankCorrelation({1, 2}, {1, 2}), 0.0);               // too few
  EXPECT_DOUBLE_EQ(rankCorrelation({1, 1, 1}, {1, 2, 3}), 0.0);         // no spread
}
