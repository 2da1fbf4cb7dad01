// Coverage of the pairs used: person pixels per grid cell and per image third, people near and
// far, their bearing in the camera and the distinct places they stood.
#include <gtest/gtest.h>

#include "../support/synthetic_pairs.hpp"
#include "thermal_lidar_calibration/core/coverage.hpp"

using namespace thermal_lidar_calibration;
using test_support::fieldsafeCamera;
using test_support::fieldsafeTruth;

namespace {

// A pair with a filled rectangle in the mask and one person of `points` at `position`.
CalibrationPair pairWith(const cv::Rect& box, const Eigen::Vector3f& position, int label = 1) {
  const CameraModel camera = fieldsafeCamera();
  CalibrationPair p;
  p.mask = cv::Mat::zeros(camera.height, camera.width, CV_8UC1);
  p.mask(box).setTo(1);
  for (int k = 0; k < 5; ++k) {
    p.points.push_back(position + Eigen::Vector3f(0, 0, 0.1f * static_cast<float>(k)));
    p.labels.push_back(label);
  }
  p.people = 1;
  return p;
}

}  // namespace

TEST(Coverage, CountsPersonPixelsPerCellAndPerThird) {
  const CameraModel camera = fieldsafeCamera();  // 640 x 512: cells 160 x 128, thirds 213 px
  std::vector<CalibrationPair> pairs;
  pairs.push_back(pairWith(cv::Rect(0, 0, 10, 10), {5, 0, 0}));       // top-left cell, left
  pairs.push_back(pairWith(cv::Rect(630, 500, 10, 12), {15, 0, 0}));  // bottom-right, right
  pairs.push_back(pairWith(cv::Rect(300, 200, 20, 5), {25, 3, 0}));   // centre third
  const Coverage c = computeCoverage(camera, pairs, {}, std::nullopt, CoverageConfig{});
  EXPECT_EQ(c.pairs, 3u);
  EXPECT_EQ(c.person_pixels, 100u + 120u + 100u);
  EXPECT_EQ(c.grid_pixels[0], 100u);
  EXPECT_EQ(c.grid_pixels[15], 120u);
  EXPECT_EQ(c.grid_pixels[1 * 4 + 1], 100u);  // x 300 -> column 1, y 200 -> row 1
  EXPECT_EQ(c.third_pixels[kLeftThird], 100u);
  EXPECT_EQ(c.third_pixels[kCentreThird], 100u);
  EXPECT_EQ(c.third_pixels[kRightThird], 120u);
  EXPECT_NEAR(c.thirdFraction(kRightThird), 120.0 / 320.0, 1e-12);
  EXPECT_NEAR(c.gridFraction(3, 3), 120.0 / 320.0, 1e-12);
  EXPECT_FALSE(c.has_bearing);
}

TEST(Coverage, RangesNearFarAndDistinctPlacesOfTheUsedPairsOnly) {
  const CameraModel camera = fieldsafeCamera();
  std::vector<CalibrationPair> pairs;
  pairs.push_back(pairWith(cv::Rect(100, 100, 5, 5), {4, 0, 0}));
  pairs.push_back(pairWith(cv::Rect(100, 100, 5, 5), {4.2f, 0.1f, 0}));  // same 1 m cell
  pairs.push_back(pairWith(cv::Rect(100, 100, 5, 5), {12, 2, 0}));
  pairs.push_back(pairWith(cv::Rect(100, 100, 5, 5), {30, 0, 0}));  // not used
  CoverageConfig config;
  config.near_far_split_m = 10.0;
  const Coverage c = computeCoverage(camera, pairs, {0, 1, 2}, std::nullopt, config);
  EXPECT_EQ(c.pairs, 3u);
  EXPECT_EQ(c.people, 3u);
  EXPECT_EQ(c.people_near, 2u);
  EXPECT_EQ(c.people_far, 1u);
  EXPECT_EQ(c.distinct_positions, 2u);
  EXPECT_NEAR(c.range_max_m, std::sqrt(12.0 * 12.0 + 2.0 * 2.0 + 0.2 * 0.2), 1e-5);
  EXPECT_NEAR(c.range_min_m, std::sqrt(16.0 + 0.2 * 0.2), 1e-5);
}

TEST(Coverage, BearingInTheCameraFrameWhenAnEstimateIsGiven) {
  // Synthetic people spread over the image: bearings within the camera's field of view
  // (FieldSAFE: 640 px at fx 772 is +-22.5 deg), some left, some right.
  test_support::SyntheticPairsOptions o;
  o.pairs = 20;
  const auto pairs = test_support::makeSyntheticPairs(fieldsafeCamera(), fieldsafeTruth(), o);
  const Coverage c =
      computeCoverage(fieldsafeCamera(), pairs, {}, fieldsafeTruth(), CoverageConfig{});
  ASSERT_TRUE(c.has_bearing);
  EXPECT_LT(c.bearing_min_deg, 0.0);
  EXPECT_GT(c.bearing_max_deg, 0.0);
  EXPECT_GT(c.bearing_min_deg, -25.0);
  EXPECT_LT(c.bearing_max_deg, 25.0);
}

TEST(Coverage, RefusesABadConfigOrAMaskOfAnotherSize) {
  const CameraModel camera = fieldsafeCamera();
  std::vector<CalibrationPair> pairs{pairWith(cv::Rect(0, 0, 2, 2), {5, 0, 0})};
  CoverageConfig config;
  config.grid_columns = 0;
  EXPECT_THROW(computeCoverage(camera, pairs, {}, std::nullopt, config), std::invalid_argument);
  pairs[0].mask = cv::Mat::zeros(10, 10, CV_8UC1);
  EXPECT_THROW(computeCoverage(camera, pairs, {}, std::nullopt, CoverageConfig{}),
               std::invalid_argument);
}
