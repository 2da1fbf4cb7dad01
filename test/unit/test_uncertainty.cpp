// The bootstrap over pairs: deterministic per seed whatever the thread count, narrower with more
// pairs, wide enough to hold the truth on pairs whose people are cut out exactly, and it stops
// when asked.
#include <gtest/gtest.h>

#include <numeric>

#include "../support/moving_pairs.hpp"
#include "../support/synthetic_pairs.hpp"
#include "thermal_lidar_calibration/core/local_refinement.hpp"
#include "thermal_lidar_calibration/core/pose_difference.hpp"
#include "thermal_lidar_calibration/core/uncertainty.hpp"
#include "thermal_lidar_calibration/core/vertical_centring.hpp"

using namespace thermal_lidar_calibration;
using test_support::fieldsafeCamera;
using test_support::fieldsafeTruth;

namespace {

std::vector<CalibrationPair> pairs(int n, std::uint64_t seed) {
  test_support::SyntheticPairsOptions o;
  o.pairs = n;
  o.seed = seed;
  o.points_per_person = 60;
  return test_support::makeSyntheticPairs(fieldsafeCamera(), fieldsafeTruth(), o);
}

std::vector<std::size_t> all(std::size_t n) {
  std::vector<std::size_t> v(n);
  std::iota(v.begin(), v.end(), std::size_t{0});
  return v;
}

// The estimate a calibration would return: the refined minimum of the data's loss.
Extrinsic estimateOn(const LossEvaluator& loss, std::size_t n) {
  return LocalRefinement(loss.withPixelRule(PixelRule::kBilinear), RefineConfig{}, 0)
      .run(fieldsafeTruth(), all(n))
      .best;
}

}  // namespace

TEST(PoseDifference, ReportsRotationAboutTheCameraAxesAndTheTranslationInCm) {
  const Extrinsic reference = fieldsafeTruth();
  Extrinsic turned = reference;
  const double angle = 0.5 * M_PI / 180.0;
  turned.rotation_vector =
      matrixToRodrigues(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitY()).toRotationMatrix() *
                        reference.rotationMatrix());
  turned.translation += Eigen::Vector3d(0.01, -0.02, 0.03);
  const PoseDifference d = poseDifference(turned, reference);
  EXPECT_NEAR(d.rotation_deg.x(), 0.0, 1e-9);
  EXPECT_NEAR(d.rotation_deg.y(), 0.5, 1e-9);
  EXPECT_NEAR(d.rotation_deg.z(), 0.0, 1e-9);
  EXPECT_NEAR(d.angle_deg, 0.5, 1e-9);
  EXPECT_TRUE(d.translation_cm.isApprox(Eigen::Vector3d(1, -2, 3), 1e-9));
  EXPECT_NEAR(asVector(poseDifference(reference, turned))[1], -0.5, 1e-9);
}

TEST(Uncertainty, SameSeedSameIntervalsWhateverTheThreadCount) {
  const auto data = pairs(25, 3);
  const LossEvaluator loss(fieldsafeCamera(), data, LossConfig{});
  const Extrinsic estimate = estimateOn(loss, data.size());
  UncertaintyConfig config = UncertaintyConfig::quick();
  config.resamples = 12;
  config.num_threads = 1;
  const Uncertainty one = estimateUncertainty(loss, estimate, all(data.size()), config);
  config.num_threads = 2;
  const Uncertainty two = estimateUncertainty(loss, estimate, all(data.size()), config);
  ASSERT_EQ(one.resamples, 12);
  ASSERT_EQ(two.resamples, 12);
  for (int b = 0; b < 12; ++b) EXPECT_EQ(one.deviations[b], two.deviations[b]) << "resample " << b;
  EXPECT_EQ(one.rotation_deg, two.rotation_deg);
  EXPECT_EQ(one.translation_cm, two.translation_cm);
  config.seed = 2;
  const Uncertainty other = estimateUncertainty(loss, estimate, all(data.size()), config);
  EXPECT_NE(one.deviations[0], other.deviations[0]) << "another seed draws other resamples";
}

TEST(Uncertainty, ResamplesOfSomePairsAreThoseOfThesePairsAlone) {
  // The bootstrap draws from some of the evaluator's pairs (the spaced ones) and reads them
  // through an evaluator over those alone: the timed resamples, and the centring with the pairs
  // that fit, must come out as from an evaluator built on those pairs only.
  auto data = pairs(30, 5);
  test_support::addMotion(data, test_support::MotionOptions{});
  const std::vector<std::size_t> picked = {1, 4, 5, 9, 12, 13, 17, 20, 22, 23, 26, 29};
  std::vector<CalibrationPair> alone;
  for (std::size_t i : picked) alone.push_back(data[i]);
  const LossConfig timed{5.0, PixelRule::kBilinear, 0.06};
  const LossEvaluator whole(fieldsafeCamera(), data, timed);
  const LossEvaluator own(fieldsafeCamera(), alone, timed);
  const Extrinsic estimate = estimateOn(own, alone.size());
  VerticalCentringConfig centring;
  const VerticalCentringOutcome centred_whole = centreVertically(whole, estimate, picked, centring, 1);
  const VerticalCentringOutcome centred_own = centreVertically(own, estimate, all(alone.size()), centring, 1);
  ASSERT_TRUE(centred_whole.applied) << centred_whole.skipped_because;
  ASSERT_EQ(centred_whole.fitting.size(), centred_own.fitting.size());
  UncertaintyConfig config = UncertaintyConfig::quick();
  config.resamples = 6;
  config.num_threads = 1;
  const Uncertainty a = estimateUncertainty(whole, centred_whole.extrinsic, picked, config, {}, TimeOffsetConfig{},
                                            &centred_whole);
  const Uncertainty b = estimateUncertainty(own, centred_own.extrinsic, all(alone.size()), config, {},
                                            TimeOffsetConfig{}, &centred_own);
  ASSERT_EQ(a.resamples, 6);
  ASSERT_EQ(b.resamples, 6);
  for (int k = 0; k < 6; ++k) {
    EXPECT_EQ(a.deviations[k], b.deviations[k]) << "resample " << k;
    EXPECT_EQ(a.time_offset_deviations_ms[k], b.time_offset_deviations_ms[k]) << "resample " << k;
  }
}

TEST(Uncertainty, IntervalsShrinkFrom20To60Pairs) {
  UncertaintyConfig config;
  config.resamples = 50;
  const auto data = pairs(60, 11);
  const LossEvaluator loss(fieldsafeCamera(), data, LossConfig{});
  const std::vector<CalibrationPair> first20(data.begin(), data.begin() + 20);
  const LossEvaluator loss20(fieldsafeCamera(), first20, LossConfig{});
  const Uncertainty u20 = estimateUncertainty(loss20, estimateOn(loss20, 20), all(20), config);
  const Uncertainty u60 = estimateUncertainty(loss, estimateOn(loss, 60), all(60), config);
  // Six axes; with 3x the pairs each half-width should fall by about sqrt(3). Allow noise per
  // axis but require the sum over the axes to fall clearly.
  double sum20 = 0, sum60 = 0;
  for (int k = 0; k < 6; ++k) {
    EXPECT_LT(u60.halfWidth(k), u20.halfWidth(k) * 1.1) << "axis " << k;
    sum20 += u20.halfWidth(k);
    sum60 += u60.halfWidth(k);
  }
  EXPECT_LT(sum60, 0.8 * sum20);
  EXPECT_EQ(u60.pairs, 60u);
  EXPECT_EQ(u60.resamples, 50);
  EXPECT_EQ(u60.deviations.size(), 50u);
}

TEST(Uncertainty, IntervalsHoldTheTruthOnExactPairs) {
  const auto data = pairs(40, 21);
  const LossEvaluator loss(fieldsafeCamera(), data, LossConfig{});
  const Extrinsic estimate = estimateOn(loss, data.size());
  UncertaintyConfig config;
  config.resamples = 50;
  config.block_pairs = 1;  // these pairs are drawn independently: single pairs are the right resample
  const Uncertainty u = estimateUncertainty(loss, estimate, all(data.size()), config);
  const Vector6d error = asVector(poseDifference(fieldsafeTruth(), estimate));
  for (int k = 0; k < 6; ++k) {
    EXPECT_GT(u.halfWidth(k), 0.0) << "axis " << k;
    EXPECT_LE(std::abs(error[k]), u.halfWidth(k)) << "axis " << k;
    EXPECT_LE(u.lower[k], u.upper[k]);
  }
}

TEST(Uncertainty, StopsWhenAskedAndRefusesTooFewPairsOrABadConfig) {
  const auto data = pairs(10, 4);
  const LossEvaluator loss(fieldsafeCamera(), data, LossConfig{});
  UncertaintyConfig config = UncertaintyConfig::quick();
  config.num_threads = 1;
  const Uncertainty u = estimateUncertainty(loss, fieldsafeTruth(), all(10), config,
                                            [](int done, int) { return done < 4; });
  EXPECT_TRUE(u.stopped);
  EXPECT_EQ(u.resamples, 4);
  EXPECT_THROW(estimateUncertainty(loss, fieldsafeTruth(), {0, 1}, config), std::invalid_argument);
  config.resamples = 1;
  EXPECT_THROW(estimateUncertainty(loss, fieldsafeTruth(), all(10), config), std::invalid_argument);
}

TEST(Uncertainty, ResamplesDrawWithReplacementInRunsOfConsecutivePairs) {
  const std::vector<std::size_t> pairs{10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20};
  const auto plain = resamplePairs(pairs, 1, 7, 0);
  ASSERT_EQ(plain.size(), pairs.size());
  EXPECT_EQ(plain, resamplePairs(pairs, 1, 7, 0)) << "same seed and index, same resample";
  EXPECT_NE(plain, resamplePairs(pairs, 1, 7, 1));
  for (std::size_t p : plain) EXPECT_TRUE(p >= 10 && p <= 20);
  const auto blocks = resamplePairs(pairs, 4, 7, 0);
  ASSERT_EQ(blocks.size(), pairs.size());
  for (std::size_t k = 0; k < blocks.size(); ++k) {
    if (k % 4 != 0) EXPECT_EQ(blocks[k], blocks[k - 1] + 1) << "entry " << k;
  }
}

// The description says what each resample's fit did beyond the refinement, as the estimate's:
// read from an evaluator with the rings' ends, it says so; without, it does not.
TEST(Uncertainty, TheDescriptionSaysWhatTheResamplesRead) {
  auto data = pairs(10, 4);
  test_support::snapToRings(data, 1.33);
  const LossEvaluator plain(fieldsafeCamera(), data, LossConfig{});
  const LossEvaluator with_ends = plain.withRingEnds(data, fieldsafeTruth(), 1.0);
  ASSERT_GT(with_ends.ringEndCount(), 0u);
  UncertaintyConfig config = UncertaintyConfig::quick();
  config.num_threads = 1;
  const auto stop_at_two = [](int done, int) { return done < 2; };
  const Uncertainty without = estimateUncertainty(plain, fieldsafeTruth(), all(10), config, stop_at_two);
  const Uncertainty with = estimateUncertainty(with_ends, fieldsafeTruth(), all(10), config, stop_at_two);
  EXPECT_FALSE(without.ring_ends);
  EXPECT_TRUE(with.ring_ends);
  EXPECT_EQ(without.method().find("rings' ends"), std::string::npos) << without.method();
  EXPECT_NE(with.method().find("reading the rings' ends"), std::string::npos) << with.method();
  Uncertainty u;
  u.block_pairs = 5;
  u.resamples = 100;
  EXPECT_EQ(u.method(), "bootstrap over pairs in blocks of 5, 100 resamples, local refinement from the estimate");
  u.timed = u.ring_ends = u.centred = true;
  EXPECT_EQ(u.method(),
            "bootstrap over pairs in blocks of 5, 100 resamples, local refinement from the estimate with the "
            "time offset reading the rings' ends, then the vertical centring");
}
