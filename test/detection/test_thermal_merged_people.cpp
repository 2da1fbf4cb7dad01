// Thermal person segmentation where people merge into one warm region, or one person falls
// apart in two: the cases that fooled the segmenter on real night street images (LLVIP).

#include "thermal_lidar_calibration/detection/thermal_person_segmenter.hpp"

#include "../support/thermal_scene.hpp"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <string>
#include <vector>

namespace thermal_lidar_calibration {
namespace {

using detection::ThermalPersonSegmenter;
using detection::ThermalSegmentation;
using detection::ThermalSegmenterConfig;
using test_support::drawPerson;
using test_support::fillKelvin;
using test_support::thermalBackground;

const cv::Size kFrame(640, 512);

std::string describe(const ThermalSegmentation& s) {
  std::string text;
  for (const auto& p : s.people) {
    text += "person " + std::to_string(p.bbox.x) + "," + std::to_string(p.bbox.y) + " " +
            std::to_string(p.bbox.width) + "x" + std::to_string(p.bbox.height) + "; ";
  }
  for (const auto& r : s.rejected) {
    text += r.reason + " " + std::to_string(r.bbox.x) + "," + std::to_string(r.bbox.y) + " " +
            std::to_string(r.bbox.width) + "x" + std::to_string(r.bbox.height) + "; ";
  }
  return text;
}

TEST(ThermalMergedPeople, TwoRidersWhoseHeadsTouchAreSplitWhenTheWholeIsNoPerson) {
  // LLVIP: two people on a scooter, their helmets touching (the valley between them dips less
  // than thermal_head_dip_fraction of the region's height), the front rider's arm reaching
  // forward to the handlebar: one region too squat for a person, so nobody was found.
  const auto riders = [](cv::Mat& image, std::vector<int> centres, bool arm) {
    for (int cx : centres) {
      drawPerson(image, cx, 150, 130, 307.0, 301.0);
      cv::circle(image, cv::Point(cx, 161), 11, cv::Scalar(std::round(test_support::countsOf(304.0))), cv::FILLED);
    }
    if (arm) fillKelvin(image, cv::Rect(238, 205, 48, 10), 301.0);  // to the handlebar
  };
  cv::Mat image = thermalBackground(kFrame, 288.0, 0.1, 61);
  riders(image, {300, 320}, true);  // helmets x 289-311 and 309-331: they touch
  const auto result = ThermalPersonSegmenter().segment(image);
  ASSERT_EQ(result.people.size(), 2u) << describe(result);
  EXPECT_LT(result.people[0].centroid.x, result.people[1].centroid.x);
  for (const auto& p : result.people) EXPECT_GT(p.bbox.height, 120) << describe(result);
  // The whole is what the detector saw before: one region, not a person.
  ThermalSegmenterConfig no_split;
  no_split.split_max_aspect = 0.01;
  const auto merged = ThermalPersonSegmenter(no_split).segment(image);
  EXPECT_TRUE(merged.people.empty()) << describe(merged);
  // Side by side without the arm: the two helmets leave the whole region without a neck.
  cv::Mat no_arm = thermalBackground(kFrame, 288.0, 0.1, 62);
  riders(no_arm, {300, 320}, false);
  EXPECT_TRUE(ThermalPersonSegmenter(no_split).segment(no_arm).people.empty());
  EXPECT_EQ(ThermalPersonSegmenter().segment(no_arm).people.size(), 2u);
  // One rider alone is one person, whatever the arm does to the valleys of the top profile.
  for (const bool arm : {false, true}) {
    cv::Mat one = thermalBackground(kFrame, 288.0, 0.1, 63);
    riders(one, {300}, arm);
    const auto alone = ThermalPersonSegmenter().segment(one);
    EXPECT_LE(alone.people.size(), 1u) << describe(alone);
  }
}

TEST(ThermalMergedPeople, AWarmPatchWithAnUnevenTopIsNotCutIntoPeople) {
  // A warm car or wall patch, too squat for a person, whose top has shallow dips: cutting it
  // would leave parts that are no person, so it stays one rejected region.
  cv::Mat image = thermalBackground(kFrame, 288.0, 0.1, 64);
  fillKelvin(image, cv::Rect(200, 220, 120, 70), 302.0);
  fillKelvin(image, cv::Rect(215, 215, 20, 5), 302.0);  // dips of 5 px: 0.04-0.08 of its height
  fillKelvin(image, cv::Rect(260, 215, 25, 5), 302.0);
  const auto result = ThermalPersonSegmenter().segment(image);
  EXPECT_TRUE(result.people.empty()) << describe(result);
  EXPECT_EQ(result.rejected.size(), 1u) << describe(result);
}

TEST(ThermalMergedPeople, PersonCutAtTheWaistByAColdBandIsJoined) {
  // LLVIP: a person whose belt (or a cable in front) is as cold as the street: the head and
  // torso pass as a short person (a wrong box), the legs fail alone.
  cv::Mat image = thermalBackground(kFrame, 288.0, 0.1, 63);
  drawPerson(image, 300, 150, 160, 307.0, 301.0);
  fillKelvin(image, cv::Rect(270, 150 + 70, 60, 8), 288.0);  // 8 px band at 44-49 % of the height
  const auto result = ThermalPersonSegmenter().segment(image);
  ASSERT_EQ(result.people.size(), 1u) << describe(result);
  EXPECT_NEAR(result.people[0].bbox.y, 150, 2);
  EXPECT_NEAR(result.people[0].bbox.height, 160, 3);
  EXPECT_TRUE(result.rejected.empty()) << describe(result);
  // A band as high as a third of the person is no thin band: the parts stay apart.
  cv::Mat wide = thermalBackground(kFrame, 288.0, 0.1, 64);
  drawPerson(wide, 300, 150, 160, 307.0, 301.0);
  fillKelvin(wide, cv::Rect(270, 150 + 70, 60, 50), 288.0);
  const auto apart = ThermalPersonSegmenter().segment(wide);
  for (const auto& p : apart.people) EXPECT_LT(p.bbox.height, 120) << describe(apart);
}

TEST(ThermalMergedPeople, AWarmBollardBelowAPersonsFeetIsNotJoinedToThePerson) {
  // LLVIP's streets have warm bollards; seen from above, one may stand just below a person's feet.
  // The stride spans more than twice the bollard's top: the body does not go on across the gap.
  cv::Mat image = thermalBackground(kFrame, 288.0, 0.1, 66);
  drawPerson(image, 300, 100, 160, 307.0, 301.0);      // feet at row 260, legs x 289-311
  fillKelvin(image, cv::Rect(296, 266, 8, 34), 303.0);  // the bollard, 6 px below
  const auto result = ThermalPersonSegmenter().segment(image);
  ASSERT_EQ(result.people.size(), 1u) << describe(result);
  EXPECT_NEAR(result.people[0].bbox.height, 160, 3) << describe(result);
}

TEST(ThermalMergedPeople, TwoPeopleOneAboveTheOtherAreNeverJoined) {
  // People walking one behind the other, seen from above: the farther one's feet end just above
  // the nearer one's head. Both are people on their own, so no join applies.
  cv::Mat image = thermalBackground(kFrame, 288.0, 0.1, 65);
  drawPerson(image, 300, 60, 120, 307.0, 301.0);   // farther: feet at row 180
  drawPerson(image, 305, 186, 150, 307.0, 301.0);  // nearer: head from row 186
  const auto result = ThermalPersonSegmenter().segment(image);
  ASSERT_EQ(result.people.size(), 2u) << describe(result);
  EXPECT_LT(result.people[0].bbox.height, 125);
  EXPECT_LT(result.people[1].bbox.height, 155);
}

}  // namespace
}  // namespace thermal_lidar_calibration
