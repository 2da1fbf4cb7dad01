// The person-by-person matcher (issue 23): regions, margins, one to one, people side by side, a
// cluster between two regions, extra regions and clusters, a wrong extrinsic.

#include "thermal_lidar_calibration/core/person_association.hpp"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include <cmath>
#include <stdexcept>

namespace tlc = thermal_lidar_calibration;

namespace {

// 320x240, f = 200 px: at 10 m a metre is 20 px. The LiDAR frame is the camera's (identity), so
// a person at x metres, 10 m ahead, is drawn at u = 160 + 20 x.
tlc::CameraModel camera() {
  tlc::CameraModel c;
  c.width = 320;
  c.height = 240;
  c.fx = c.fy = 200;
  c.cx = 160;
  c.cy = 120;
  return c;
}

constexpr double kRange = 10.0;

// A person's LiDAR points: a 0.5 m x 1.7 m grid of points at x, kRange ahead.
void addPerson(std::vector<Eigen::Vector3f>& points, std::vector<std::int32_t>& labels, std::int32_t label,
               double x) {
  for (int i = 0; i < 5; ++i) {
    for (int j = 0; j < 12; ++j) {
      points.emplace_back(static_cast<float>(x - 0.2 + 0.1 * i), static_cast<float>(-0.8 + 0.15 * j),
                          static_cast<float>(kRange));
      labels.push_back(label);
    }
  }
}

// The region of a person at x (what the points above cover), with id `id`.
void drawPerson(cv::Mat& mask, int id, double x) {
  const int u0 = static_cast<int>(std::lround(160 + 20 * (x - 0.25)));
  mask(cv::Rect(u0, 120 - 17, 10, 36)).setTo(id);
}

struct Scene {
  cv::Mat mask = cv::Mat::zeros(240, 320, CV_8UC1);
  std::vector<Eigen::Vector3f> points;
  std::vector<std::int32_t> labels;
  tlc::FrameAssociation associate(const tlc::Extrinsic& e = {}, tlc::AssociationConfig config = {}) const {
    return tlc::associateClusters(camera(), tlc::personRegions(mask), points, labels, e, config);
  }
};

// The region the cluster `label` was matched to, 0 if none.
int regionOf(const tlc::FrameAssociation& a, std::int32_t label) {
  for (const tlc::ClusterMatch& m : a.matches) {
    if (m.label == label) return m.region;
  }
  return 0;
}

}  // namespace

TEST(PersonRegions, IdsAreNumberedByValueAndBinaryMasksByComponent) {
  cv::Mat ids = cv::Mat::zeros(20, 30, CV_16UC1);
  ids(cv::Rect(1, 1, 3, 3)).setTo(900);
  ids(cv::Rect(4, 1, 3, 3)).setTo(40);  // touching 900: still its own region
  int n = 0;
  cv::Mat regions = tlc::personRegions(ids, &n);
  EXPECT_EQ(n, 2);
  EXPECT_EQ(regions.type(), CV_16UC1);
  EXPECT_EQ(regions.at<std::uint16_t>(2, 5), 1);  // 40 -> 1
  EXPECT_EQ(regions.at<std::uint16_t>(2, 2), 2);  // 900 -> 2

  cv::Mat binary = cv::Mat::zeros(20, 30, CV_8UC1);
  binary(cv::Rect(1, 1, 3, 3)).setTo(255);
  binary(cv::Rect(10, 1, 3, 3)).setTo(255);
  regions = tlc::personRegions(binary, &n);
  EXPECT_EQ(n, 2);
  EXPECT_NE(regions.at<std::uint16_t>(2, 2), regions.at<std::uint16_t>(2, 11));
  EXPECT_THROW(tlc::personRegions(cv::Mat::zeros(4, 4, CV_32FC1)), std::invalid_argument);
}

TEST(PersonAssociation, EachClusterGoesToItsOwnRegionOneToOne) {
  Scene s;
  addPerson(s.points, s.labels, 7, -3.0);
  addPerson(s.points, s.labels, 3, 2.0);
  drawPerson(s.mask, 1, 2.0);
  drawPerson(s.mask, 2, -3.0);
  const tlc::FrameAssociation a = s.associate();
  ASSERT_EQ(a.matches.size(), 2u);
  EXPECT_EQ(a.clusters, 2);
  EXPECT_EQ(a.regions, 2);
  EXPECT_EQ(regionOf(a, 3), 1);
  EXPECT_EQ(regionOf(a, 7), 2);
  EXPECT_EQ(a.matches[0].label, 3);  // by increasing label
  EXPECT_GT(a.matches[0].overlap, 0.95);
  EXPECT_EQ(a.matches[0].second, 0.0);
}

TEST(PersonAssociation, PeopleSideBySideWithTheirOwnIdsAreBothMatched) {
  Scene s;
  addPerson(s.points, s.labels, 1, 0.0);
  addPerson(s.points, s.labels, 2, 0.5);  // shoulder to shoulder: the regions touch
  drawPerson(s.mask, 4, 0.0);
  drawPerson(s.mask, 9, 0.5);
  const tlc::FrameAssociation a = s.associate();
  ASSERT_EQ(a.matches.size(), 2u);
  EXPECT_EQ(regionOf(a, 1), 1);
  EXPECT_EQ(regionOf(a, 2), 2);
}

TEST(PersonAssociation, TwoClustersOnOneRegionAreBothLeftOut) {
  // The same two people in a binary mask: one merged region for both.
  Scene s;
  addPerson(s.points, s.labels, 1, 0.0);
  addPerson(s.points, s.labels, 2, 0.5);
  drawPerson(s.mask, 255, 0.0);
  drawPerson(s.mask, 255, 0.5);
  addPerson(s.points, s.labels, 5, 4.0);  // and a third person alone, who is matched
  drawPerson(s.mask, 255, 4.0);
  const tlc::FrameAssociation a = s.associate();
  EXPECT_EQ(a.regions, 2);
  ASSERT_EQ(a.matches.size(), 1u);
  EXPECT_EQ(a.matches[0].label, 5);
}

TEST(PersonAssociation, AClusterBetweenTwoRegionsIsLeftOut) {
  Scene s;
  addPerson(s.points, s.labels, 1, 0.0);
  // Two regions with a cold gap where the person stands: a fifth of its points within reach of
  // one, two fifths of the other.
  s.mask(cv::Rect(160 - 5 - 8, 120 - 17, 8, 36)).setTo(1);
  s.mask(cv::Rect(160 + 5, 120 - 17, 8, 36)).setTo(2);
  s.mask(cv::Rect(160 - 5, 120 - 17, 10, 36)).setTo(0);
  tlc::AssociationConfig config;
  config.tolerance_px = 3.0;
  EXPECT_TRUE(s.associate({}, config).matches.empty());
}

TEST(PersonAssociation, TheBestRegionMustWinByTheMargin) {
  // A person whose region is split at a waist-high cold band: the lower part (legs) takes 40 % of
  // the points, the upper part 60 %. Margin 0.4: left out; margin 0.1: the upper part wins.
  Scene s;
  addPerson(s.points, s.labels, 1, 0.0);
  s.mask(cv::Rect(155, 120 - 17, 10, 36)).setTo(1);
  // Rows of points at v = 104 + 3 j (j = 0..11); j < 7 (v <= 122) upper, j >= 7 lower.
  s.mask(cv::Rect(155, 123, 10, 16)).setTo(2);
  tlc::AssociationConfig config;
  config.tolerance_px = 0.0;
  config.min_overlap = 0.5;
  config.margin = 0.4;
  const tlc::FrameAssociation strict = s.associate({}, config);
  EXPECT_TRUE(strict.matches.empty());
  config.margin = 0.1;
  const tlc::FrameAssociation loose = s.associate({}, config);
  ASSERT_EQ(loose.matches.size(), 1u);
  EXPECT_EQ(loose.matches[0].region, 1);
  EXPECT_NEAR(loose.matches[0].overlap, 7.0 / 12.0, 1e-9);
  EXPECT_NEAR(loose.matches[0].second, 5.0 / 12.0, 1e-9);
}

TEST(PersonAssociation, ExtraRegionsCostNothingAndExtraClustersAreDropped) {
  Scene s;
  addPerson(s.points, s.labels, 1, -2.0);
  drawPerson(s.mask, 1, -2.0);
  drawPerson(s.mask, 2, 3.0);   // a warm post: a region with no cluster
  addPerson(s.points, s.labels, 2, 5.5);  // a cluster on no region (a person the camera missed)
  const tlc::FrameAssociation a = s.associate();
  ASSERT_EQ(a.matches.size(), 1u);
  EXPECT_EQ(a.matches[0].label, 1);

  tlc::CalibrationPair frame;
  frame.regions = tlc::personRegions(s.mask);
  frame.points = s.points;
  frame.labels = s.labels;
  frame.point_time_s.assign(s.points.size(), 0.01f);
  frame.candidate_index = 42;
  const std::optional<tlc::CalibrationPair> pair = tlc::associatedPair(frame, a);
  ASSERT_TRUE(pair);
  EXPECT_EQ(pair->rule, tlc::PairRule::kAssociation);
  EXPECT_EQ(pair->candidate_index, 42u);
  EXPECT_EQ(pair->people, 1);
  EXPECT_EQ(pair->points.size(), 60u);
  EXPECT_EQ(pair->point_time_s.size(), 60u);
  for (std::int32_t label : pair->labels) EXPECT_EQ(label, 1);
  // The whole mask stays person pixels, the post included.
  EXPECT_EQ(cv::countNonZero(pair->mask), 2 * 10 * 36);
  EXPECT_FALSE(tlc::associatedPair(frame, tlc::FrameAssociation{}));
}

TEST(PersonAssociation, AWrongExtrinsicMatchesNobody) {
  // 5 deg about the camera's y axis moves a person at 10 m by ~0.87 m (17 px): off their region
  // and short of the next one. A cluster that a wrong extrinsic puts squarely on another person
  // would be matched: what keeps that out of a calibration is the refit on the count rule's
  // pairs (association_refit.hpp), not the matcher.
  Scene s;
  addPerson(s.points, s.labels, 1, -3.0);
  addPerson(s.points, s.labels, 2, 3.0);
  drawPerson(s.mask, 1, -3.0);
  drawPerson(s.mask, 2, 3.0);
  tlc::Extrinsic wrong;
  wrong.rotation_vector = Eigen::Vector3d(0, 5.0 * M_PI / 180.0, 0);
  EXPECT_TRUE(s.associate(wrong).matches.empty());
  EXPECT_EQ(s.associate().matches.size(), 2u);
}

TEST(PersonAssociation, BadInputIsRefused) {
  Scene s;
  addPerson(s.points, s.labels, 1, 0.0);
  EXPECT_THROW(tlc::associateClusters(camera(), cv::Mat::zeros(10, 10, CV_16UC1), s.points, s.labels, {}, {}),
               std::invalid_argument);
  s.labels.pop_back();
  EXPECT_THROW(s.associate(), std::invalid_argument);
  tlc::AssociationConfig config;
  config.margin = 1.5;
  EXPECT_THROW(config.validate(), std::invalid_argument);
}
