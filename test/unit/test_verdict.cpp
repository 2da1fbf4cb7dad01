// The verdict: the worst finding decides, each finding says what to do, and the thresholds are
// checked.
#include <gtest/gtest.h>

#include "thermal_lidar_calibration/core/verdict.hpp"

using namespace thermal_lidar_calibration;

namespace {

// Coverage that passes every default check: 60 pairs, people in all thirds, near and far.
Coverage wellCovered() {
  Coverage c;
  c.grid_columns = c.grid_rows = 4;
  c.grid_pixels.assign(16, 100);
  c.third_pixels = {500, 600, 500};
  c.person_pixels = 1600;
  c.pairs = 60;
  c.people = 80;
  c.people_near = 30;
  c.people_far = 50;
  c.near_far_split_m = 10.0;
  c.distinct_positions = 70;
  return c;
}

Uncertainty tight() {
  Uncertainty u;
  u.resamples = 50;
  u.rotation_deg = Eigen::Vector3d(0.02, 0.03, 0.02);
  u.translation_cm = Eigen::Vector3d(0.5, 0.6, 1.2);
  return u;
}

bool mentions(const VerdictReport& r, const std::string& text) {
  for (const auto& reason : r.reasons) {
    if (reason.find(text) != std::string::npos) return true;
  }
  return false;
}

}  // namespace

TEST(Verdict, GoodWhenCoveredAndTight) {
  const VerdictReport r = judgeQuality(wellCovered(), tight(), VerdictConfig{});
  EXPECT_EQ(r.verdict, Verdict::kGood);
  ASSERT_EQ(r.reasons.size(), 1u);
  EXPECT_TRUE(r.missing_regions.empty());
  EXPECT_STREQ(toString(r.verdict), "good");
}

TEST(Verdict, EmptyLeftThirdIsCollectMoreAndNamesTheRegionAndWhatToDo) {
  Coverage c = wellCovered();
  c.third_pixels = {0, 900, 700};
  const VerdictReport r = judgeQuality(c, tight(), VerdictConfig{});
  EXPECT_EQ(r.verdict, Verdict::kCollectMore);
  EXPECT_STREQ(toString(r.verdict), "collect_more");
  EXPECT_EQ(r.reasons.front(), "no people in the left third of the image: have people walk there");
  EXPECT_EQ(r.missing_regions, std::vector<std::string>{"left"});
}

TEST(Verdict, AFewPeopleInAThirdIsUsable) {
  Coverage c = wellCovered();
  c.third_pixels = {80, 900, 620};  // 5 % on the left
  const VerdictReport r = judgeQuality(c, tight(), VerdictConfig{});
  EXPECT_EQ(r.verdict, Verdict::kUsable);
  EXPECT_TRUE(mentions(r, "few people in the left third of the image (5.0 %"));
  EXPECT_TRUE(r.missing_regions.empty());
}

TEST(Verdict, WideIntervalsNameTheAxisAndTheThresholds) {
  Uncertainty u = tight();
  u.translation_cm.z() = 3.5;  // usable (<= 5 cm)
  VerdictReport r = judgeQuality(wellCovered(), u, VerdictConfig{});
  EXPECT_EQ(r.verdict, Verdict::kUsable);
  EXPECT_TRUE(mentions(r, "translation along the camera's z axis is uncertain by +-3.50 cm"));
  u.rotation_deg.x() = 0.8;  // beyond usable
  r = judgeQuality(wellCovered(), u, VerdictConfig{});
  EXPECT_EQ(r.verdict, Verdict::kCollectMore);
  EXPECT_TRUE(mentions(r, "rotation about the camera's x axis is uncertain by +-0.800 deg"));
  EXPECT_NE(r.reasons.front().find("rotation"), std::string::npos) << "worst first";
}

TEST(Verdict, FewPairsNoNearPeopleAndFewPlaces) {
  Coverage c = wellCovered();
  c.pairs = 12;
  c.people_near = 0;
  c.distinct_positions = 10;
  const VerdictReport r = judgeQuality(c, tight(), VerdictConfig{});
  EXPECT_EQ(r.verdict, Verdict::kCollectMore);
  EXPECT_TRUE(mentions(r, "only 12 pairs used (usable from 20, good from 40): keep collecting"));
  EXPECT_TRUE(mentions(r, "no people nearer than 10 m: have people walk closer"));
  EXPECT_TRUE(mentions(r, "people stood in only 10 distinct places"));
}

TEST(Verdict, OnePersonNearIsOnePersonAndTwoArePeople) {
  Coverage c = wellCovered();
  c.people_near = 1;
  EXPECT_TRUE(mentions(judgeQuality(c, tight(), VerdictConfig{}), "only 1 person nearer than 10 m: have people walk closer"));
  c.people_near = 2;
  EXPECT_TRUE(mentions(judgeQuality(c, tight(), VerdictConfig{}), "only 2 people nearer than 10 m"));
}

TEST(Verdict, WithoutAnUncertaintyAtBestUsable) {
  const VerdictReport r = judgeQuality(wellCovered(), std::nullopt, VerdictConfig{});
  EXPECT_EQ(r.verdict, Verdict::kUsable);
  EXPECT_TRUE(mentions(r, "no uncertainty estimate yet"));
}

TEST(Verdict, ThresholdsAreConfigurableAndChecked) {
  VerdictConfig config;
  config.good_rotation_deg = 0.01;  // stricter than the estimate's 0.03
  EXPECT_EQ(judgeQuality(wellCovered(), tight(), config).verdict, Verdict::kUsable);
  config.usable_rotation_deg = 0.005;  // good above usable
  try {
    judgeQuality(wellCovered(), tight(), config);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("quality_good_rotation_deg"), std::string::npos)
        << e.what();
  }
  config = VerdictConfig{};
  config.good_third_fraction = 0.5;
  EXPECT_THROW(judgeQuality(wellCovered(), tight(), config), std::invalid_argument);
}

TEST(Verdict, AFitThatLeavesThePointsOffTheirMasksIsCollectMoreWhateverTheIntervals) {
  // A fit carried by mismatched pairs can have tight intervals and good coverage (the bootstrap
  // refines from it and stays there); its loss gives it away (measured 2.6-24 px; typical
  // 0.03-0.2 px).
  const VerdictReport bad = judgeQuality(wellCovered(), tight(), VerdictConfig{}, 2.64);
  EXPECT_EQ(bad.verdict, Verdict::kCollectMore);
  ASSERT_FALSE(bad.reasons.empty());
  EXPECT_NE(bad.reasons.front().find("2.64 px off their masks"), std::string::npos) << bad.reasons.front();
  EXPECT_EQ(judgeQuality(wellCovered(), tight(), VerdictConfig{}, 0.05).verdict, Verdict::kGood);
  VerdictConfig lax;
  lax.max_loss_px = 5.0;
  EXPECT_EQ(judgeQuality(wellCovered(), tight(), lax, 2.64).verdict, Verdict::kGood);
  lax.max_loss_px = -1.0;
  EXPECT_THROW(judgeQuality(wellCovered(), tight(), lax, 0.05), std::invalid_argument);
}
