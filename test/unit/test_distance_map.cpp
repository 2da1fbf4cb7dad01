// The distance map must equal a brute-force L1 search everywhere, including off the image.
#include "thermal_lidar_calibration/core/distance_map.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

using thermal_lidar_calibration::DistanceMap;

namespace {

cv::Mat randomMask(int w, int h, int blobs, unsigned seed) {
  std::mt19937 rng(seed);
  cv::Mat m = cv::Mat::zeros(h, w, CV_8UC1);
  for (int b = 0; b < blobs; ++b) {
    const int x = static_cast<int>(rng() % (w - 6)) + 3, y = static_cast<int>(rng() % (h - 8)) + 4;
    for (int v = y - 3; v <= y + 3; ++v)
      for (int u = x - 1; u <= x + 1; ++u) m.at<std::uint8_t>(v, u) = 1;
  }
  return m;
}

float bruteForce(const cv::Mat& m, int u, int v) {
  float best = 1e30f;
  for (int y = 0; y < m.rows; ++y)
    for (int x = 0; x < m.cols; ++x)
      if (m.at<std::uint8_t>(y, x)) best = std::min(best, float(std::abs(u - x) + std::abs(v - y)));
  return best;
}

}  // namespace

TEST(DistanceMap, ExactL1InsideAndOutsideTheImageDespiteTheCrop) {
  const cv::Mat mask = randomMask(48, 36, 3, 1);
  const DistanceMap map(mask);
  EXPECT_LT(map.width() * map.height(), 48 * 36);  // cropped to the people's box
  for (int v = -10; v < 46; v += 3)
    for (int u = -12; u < 60; u += 2) ASSERT_EQ(map.atPixel(u, v), bruteForce(mask, u, v)) << u << "," << v;
}

TEST(DistanceMap, NearestRoundsToThePixelCentreThenMeasures) {
  cv::Mat mask = cv::Mat::zeros(20, 30, CV_8UC1);
  mask.at<std::uint8_t>(10, 15) = 1;
  const DistanceMap map(mask);
  EXPECT_EQ(map.nearest(15.4f, 10.4f), 0.0f);
  EXPECT_EQ(map.nearest(15.6f, 10.0f), 1.0f);   // rounds to 16
  EXPECT_EQ(map.nearest(14.5f, 10.0f), 0.0f);   // a tie rounds up, to 15
  EXPECT_EQ(map.nearest(-5.2f, 10.0f), 20.0f);  // off the image: |-5 - 15|
  EXPECT_EQ(map.nearest(100.0f, -40.0f), 85.0f + 50.0f);
}

TEST(DistanceMap, BilinearIsExactAtCentresAndLinearBetween) {
  cv::Mat mask = cv::Mat::zeros(20, 30, CV_8UC1);
  mask.at<std::uint8_t>(10, 15) = 1;
  const DistanceMap map(mask);
  EXPECT_FLOAT_EQ(map.bilinear(15.0f, 10.0f), 0.0f);
  EXPECT_FLOAT_EQ(map.bilinear(12.0f, 10.0f), 3.0f);
  EXPECT_FLOAT_EQ(map.bilinear(12.25f, 10.0f), 2.75f);
  EXPECT_FLOAT_EQ(map.bilinear(-3.5f, 10.0f), 18.5f);  // off the image, still exact L1
  EXPECT_FLOAT_EQ(map.bilinear(15.0f, 13.5f), 3.5f);
}

TEST(DistanceMap, FarAwayAndNaNProjectionsCostTheCapPlusTheBoxValue) {
  // z -> 0+ projects to infinity (or NaN when x = 0 too): the distance outside the box is capped,
  // NaN clamps to the box corner, and the result stays finite.
  cv::Mat mask = cv::Mat::zeros(20, 30, CV_8UC1);
  mask.at<std::uint8_t>(10, 15) = 1;
  const DistanceMap map(mask);
  const float cap = DistanceMap::kOffBoxCap;
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const int right = map.x0() + map.width() - 1;
  EXPECT_EQ(map.nearest(1e7f, 10.0f), cap + map.atPixel(right, 10));
  EXPECT_EQ(map.nearest(inf, 10.0f), cap + map.atPixel(right, 10));
  EXPECT_EQ(map.nearest(nan, nan), cap + map.atPixel(map.x0(), map.y0()));
  EXPECT_EQ(map.bilinear(-inf, 10.0f), cap + map.atPixel(map.x0(), 10));
  EXPECT_EQ(map.bilinear(nan, nan), cap + map.atPixel(map.x0(), map.y0()));
  EXPECT_EQ(map.nearest(-5.2f, 10.0f), 20.0f);  // below the cap nothing changes
}

TEST(DistanceMap, RejectsAMaskWithoutPeople) {
  EXPECT_THROW(DistanceMap(cv::Mat::zeros(10, 10, CV_8UC1)), std::invalid_argument);
}

// The map a caller builds once for every evaluator of its pair: the same numbers as its own, and
// null (not a throw) for the masks the evaluator itself reports with the pair's number.
TEST(DistanceMap, SharedMapIsTheSameMapOrNullForAMaskItCannotRead) {
  const cv::Mat mask = randomMask(48, 36, 3, 2);
  const auto shared = thermal_lidar_calibration::sharedDistanceMap(mask);
  ASSERT_TRUE(shared);
  const DistanceMap own(mask);
  EXPECT_EQ(shared->x0(), own.x0());
  EXPECT_EQ(shared->y0(), own.y0());
  ASSERT_EQ(shared->width(), own.width());
  ASSERT_EQ(shared->height(), own.height());
  for (int v = -4; v < 40; v += 5)
    for (int u = -4; u < 52; u += 3) ASSERT_EQ(shared->atPixel(u, v), own.atPixel(u, v)) << u << "," << v;
  EXPECT_FALSE(thermal_lidar_calibration::sharedDistanceMap(cv::Mat::zeros(10, 10, CV_8UC1)));
  EXPECT_FALSE(thermal_lidar_calibration::sharedDistanceMap(cv::Mat()));
  EXPECT_FALSE(thermal_lidar_calibration::sharedDistanceMap(cv::Mat::ones(10, 10, CV_32FC1)));
}
