// Counting people in masks (ids or binary, 8- and 16-bit) and in labelled LiDAR clusters.

#include "thermal_lidar_calibration/core/person_counter.hpp"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include <stdexcept>

namespace tlc = thermal_lidar_calibration;

namespace {

void fill(cv::Mat& mask, int x, int y, int w, int h, double value) {
  mask(cv::Rect(x, y, w, h)).setTo(value);
}

}  // namespace

TEST(CountMaskPeople, EmptyAndBackgroundOnly) {
  EXPECT_EQ(tlc::countMaskPeople(cv::Mat::zeros(48, 64, CV_8UC1)), 0);
  EXPECT_EQ(tlc::countMaskPeople(cv::Mat::zeros(48, 64, CV_16UC1)), 0);
  EXPECT_EQ(tlc::countMaskPeople(cv::Mat()), 0);
}

TEST(CountMaskPeople, DistinctIdsAreCountedEvenWhenTouching) {
  cv::Mat mask = cv::Mat::zeros(48, 64, CV_8UC1);
  fill(mask, 5, 5, 10, 20, 1);
  fill(mask, 15, 5, 10, 20, 2);   // touches id 1
  fill(mask, 40, 10, 5, 5, 7);
  fill(mask, 50, 30, 5, 5, 7);    // same id, split into two blobs: still one person
  EXPECT_EQ(tlc::countMaskPeople(mask), 3);
}

TEST(CountMaskPeople, SingleValueMaskCountsEightConnectedComponents) {
  cv::Mat mask = cv::Mat::zeros(48, 64, CV_8UC1);
  fill(mask, 2, 2, 5, 5, 255);
  fill(mask, 20, 20, 4, 4, 255);
  fill(mask, 40, 5, 3, 3, 255);
  EXPECT_EQ(tlc::countMaskPeople(mask), 3);

  // Two blobs touching only at a diagonal corner are one 8-connected component.
  cv::Mat diagonal = cv::Mat::zeros(20, 20, CV_8UC1);
  fill(diagonal, 2, 2, 4, 4, 1);   // covers (2..5, 2..5)
  fill(diagonal, 6, 6, 4, 4, 1);   // starts at (6, 6): diagonal neighbour of (5, 5)
  EXPECT_EQ(tlc::countMaskPeople(diagonal), 1);

  // A one-pixel gap separates them.
  cv::Mat apart = cv::Mat::zeros(20, 20, CV_8UC1);
  fill(apart, 2, 2, 4, 4, 1);
  fill(apart, 7, 7, 4, 4, 1);
  EXPECT_EQ(tlc::countMaskPeople(apart), 2);
}

TEST(CountMaskPeople, SixteenBitMasks) {
  cv::Mat ids = cv::Mat::zeros(30, 40, CV_16UC1);
  fill(ids, 1, 1, 5, 5, 1000);
  fill(ids, 10, 1, 5, 5, 65535);
  fill(ids, 20, 1, 5, 5, 256);   // would alias with 0 if truncated to 8 bits
  EXPECT_EQ(tlc::countMaskPeople(ids), 3);

  cv::Mat binary = cv::Mat::zeros(30, 40, CV_16UC1);
  fill(binary, 1, 1, 5, 5, 65535);
  fill(binary, 20, 20, 5, 5, 65535);
  EXPECT_EQ(tlc::countMaskPeople(binary), 2);
}

// The count skips background eight bytes at a time: a lone id pixel is counted at every column,
// including the ends of rows whose width is not a multiple of the word, and in a view into a
// larger mask (rows not contiguous).
TEST(CountMaskPeople, ALonePixelCountsWhereverItLies) {
  for (const int type : {CV_8UC1, CV_16UC1}) {
    for (const int width : {1, 3, 8, 13, 37}) {
      for (int c = 0; c < width; ++c) {
        cv::Mat ids = cv::Mat::zeros(3, width, type);
        fill(ids, c, 1, 1, 1, type == CV_8UC1 ? 9 : 700);
        EXPECT_EQ(tlc::countMaskPeople(ids), 1) << "width " << width << " column " << c;
        if (c + 1 < width) {
          fill(ids, width - 1, 2, 1, 1, 4);
          EXPECT_EQ(tlc::countMaskPeople(ids), 2) << "width " << width << " column " << c;
        }
      }
    }
    cv::Mat big = cv::Mat::zeros(10, 50, type);
    cv::Mat view = big(cv::Rect(3, 2, 21, 5));
    fill(view, 20, 0, 1, 1, 5);
    fill(view, 0, 4, 1, 1, 6);
    fill(big, 30, 0, 5, 5, 7);  // outside the view
    EXPECT_EQ(tlc::countMaskPeople(view), 2);
  }
}

TEST(CountMaskPeople, BadTypeThrows) {
  EXPECT_THROW(tlc::countMaskPeople(cv::Mat::zeros(10, 10, CV_32FC1)), std::invalid_argument);
  EXPECT_THROW(tlc::countMaskPeople(cv::Mat::zeros(10, 10, CV_8UC3)), std::invalid_argument);
  EXPECT_THROW(tlc::countMaskPeople(cv::Mat::zeros(10, 10, CV_32SC1)), std::invalid_argument);
  EXPECT_THROW(tlc::binarizeMask(cv::Mat::zeros(10, 10, CV_8UC3)), std::invalid_argument);
}

TEST(BinarizeMask, OneOnPeopleZeroElsewhere) {
  cv::Mat ids = cv::Mat::zeros(10, 12, CV_16UC1);
  fill(ids, 1, 1, 2, 2, 300);
  fill(ids, 5, 5, 3, 1, 1);
  const cv::Mat binary = tlc::binarizeMask(ids);
  ASSERT_EQ(binary.type(), CV_8UC1);
  ASSERT_EQ(binary.size(), ids.size());
  for (int r = 0; r < ids.rows; ++r) {
    for (int c = 0; c < ids.cols; ++c) {
      EXPECT_EQ(binary.at<std::uint8_t>(r, c), ids.at<std::uint16_t>(r, c) != 0 ? 1 : 0)
          << "at row " << r << ", col " << c;
    }
  }
  EXPECT_EQ(cv::countNonZero(binary), 4 + 3);

  cv::Mat eight = cv::Mat::zeros(4, 4, CV_8UC1);
  eight.at<std::uint8_t>(1, 2) = 255;
  const cv::Mat b8 = tlc::binarizeMask(eight);
  EXPECT_EQ(b8.at<std::uint8_t>(1, 2), 1);
  EXPECT_EQ(cv::sum(b8)[0], 1.0);
}

TEST(ClusterSizes, PointsPerLabel) {
  const auto sizes = tlc::clusterSizes({4, 4, 9, 4, -1, 9});
  ASSERT_EQ(sizes.size(), 3u);
  EXPECT_EQ(sizes.at(4), 3);
  EXPECT_EQ(sizes.at(9), 2);
  EXPECT_EQ(sizes.at(-1), 1);
  EXPECT_TRUE(tlc::clusterSizes({}).empty());
}
