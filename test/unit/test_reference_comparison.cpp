// The comparison with a transform the user already has (the paper's Table 2): the difference per
// camera axis, both losses on the same pairs, and whether each difference is within the
// interval. Also the whole assessment after a calibration.
#include <gtest/gtest.h>

#include "../support/synthetic_pairs.hpp"
#include "thermal_lidar_calibration/core/quality_assessment.hpp"
#include "thermal_lidar_calibration/core/reference_comparison.hpp"

using namespace thermal_lidar_calibration;
using test_support::fieldsafeCamera;
using test_support::fieldsafeTruth;

namespace {

std::vector<CalibrationPair> pairs(int n, std::uint64_t seed) {
  test_support::SyntheticPairsOptions o;
  o.pairs = n;
  o.seed = seed;
  o.points_per_person = 50;
  return test_support::makeSyntheticPairs(fieldsafeCamera(), fieldsafeTruth(), o);
}

// Algorithm 1, short: what the quality is assessed on need not be the default's fit.
CalibrationResult quickFit(const std::vector<CalibrationPair>& data) {
  CalibrationConfig config;
  config.algorithm = Algorithm::kPlain;
  config.evolution.population_size = 150;
  config.evolution.max_iterations = 100;
  config.seed = 2;
  return calibrate(fieldsafeCamera(), data, config);
}

}  // namespace

TEST(ReferenceComparison, DifferencePerAxisAndBothLossesOnTheSamePairs) {
  const auto data = pairs(20, 9);
  const LossEvaluator loss(fieldsafeCamera(), data, LossConfig{});
  Extrinsic reference = fieldsafeTruth();
  reference.translation += Eigen::Vector3d(0.05, 0.0, 0.0);  // 5 cm sideways
  const std::vector<std::size_t> used{0, 1, 2, 3, 4, 5, 6, 7, 8, 9};
  Uncertainty u;
  u.resamples = 50;
  u.rotation_deg = Eigen::Vector3d::Constant(0.1);
  u.translation_cm = Eigen::Vector3d::Constant(2.0);
  const ReferenceComparison c = compareWithReference(loss, fieldsafeTruth(), reference, used, u);
  EXPECT_NEAR(c.difference.translation_cm.x(), -5.0, 1e-9);
  EXPECT_NEAR(c.difference.angle_deg, 0.0, 1e-9);
  EXPECT_EQ(c.pairs, 10u);
  EXPECT_NEAR(c.our_loss, loss.loss(fieldsafeTruth(), used), 1e-12);
  EXPECT_NEAR(c.reference_loss, loss.loss(reference, used), 1e-12);
  EXPECT_GT(c.reference_loss, c.our_loss + 0.2) << "5 cm at 4-20 m is 2-10 px sideways";
  ASSERT_TRUE(c.within_uncertainty.has_value());
  const std::array<bool, 6> expected{true, true, true, false, true, true};
  EXPECT_EQ(*c.within_uncertainty, expected);
  EXPECT_FALSE(compareWithReference(loss, fieldsafeTruth(), reference, used, std::nullopt)
                   .within_uncertainty.has_value());
}

TEST(QualityAssessment, AfterACalibrationTheTruthAsReferenceIsWithinTheIntervals) {
  const auto data = pairs(40, 12);
  const CalibrationResult result = quickFit(data);
  QualityConfig quality;
  quality.uncertainty.resamples = 50;
  const QualityAssessment q =
      assessQuality(fieldsafeCamera(), data, result, quality, 5.0, fieldsafeTruth());
  ASSERT_TRUE(q.uncertainty.has_value());
  EXPECT_EQ(q.uncertainty->resamples, 50);
  EXPECT_EQ(q.coverage.pairs, result.pairs_used);
  ASSERT_TRUE(q.reference.has_value());
  for (int k = 0; k < 6; ++k) EXPECT_TRUE((*q.reference->within_uncertainty)[k]) << "axis " << k;
  EXPECT_NEAR(q.reference->our_loss, result.loss, 1e-9);
  EXPECT_FALSE(q.verdict.reasons.empty());

  quality.uncertainty_enabled = false;
  const QualityAssessment coverage_only =
      assessQuality(fieldsafeCamera(), data, result, quality, 5.0);
  EXPECT_FALSE(coverage_only.uncertainty.has_value());
  EXPECT_FALSE(coverage_only.reference.has_value());
}

// Issue 24: the bootstrap draws only from the pairs the skip rule made. Pairs of the final round
// (outside_skip_rule) see the scene of the frame beside them again: drawn as if independent they
// would narrow the intervals without a new scene behind it.
TEST(QualityAssessment, TheBootstrapLeavesOutThePairsOutsideTheSkipRule) {
  auto data = pairs(40, 12);
  for (std::size_t i = 0; i < data.size(); i += 2) data[i].outside_skip_rule = true;
  const CalibrationResult result = quickFit(data);
  std::size_t spaced_used = 0;
  for (std::size_t i = 0; i < data.size(); ++i) spaced_used += result.inliers[i] && !data[i].outside_skip_rule ? 1 : 0;
  ASSERT_GE(spaced_used, 3u);
  QualityConfig quality;
  quality.uncertainty.resamples = 20;
  const QualityAssessment q = assessQuality(fieldsafeCamera(), data, result, quality, 5.0);
  ASSERT_TRUE(q.uncertainty.has_value());
  EXPECT_EQ(q.uncertainty->pairs, spaced_used);
  EXPECT_EQ(q.coverage.pairs, result.pairs_used);  // the rest of the assessment reads them all

  // Fewer than 3 spaced pairs: the bootstrap takes them all rather than none.
  for (CalibrationPair& p : data) p.outside_skip_rule = true;
  const QualityAssessment all = assessQuality(fieldsafeCamera(), data, result, quality, 5.0);
  ASSERT_TRUE(all.uncertainty.has_value());
  EXPECT_EQ(all.uncertainty->pairs, result.pairs_used);
}
