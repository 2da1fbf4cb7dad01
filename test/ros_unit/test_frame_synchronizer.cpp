// FrameSynchronizer offline (no ros::init, no roscore): triples matched within sync_slop.

#include "thermal_lidar_calibration/ros/frame_synchronizer.hpp"

#include <boost/make_shared.hpp>
#include <gtest/gtest.h>

#include <vector>

using thermal_lidar_calibration::ros_io::FrameSynchronizer;

namespace {

sensor_msgs::Image::ConstPtr image(double t) {
  auto m = boost::make_shared<sensor_msgs::Image>();
  m->header.stamp.fromSec(t);
  return m;
}
sensor_msgs::PointCloud2::ConstPtr cloud(double t) {
  auto m = boost::make_shared<sensor_msgs::PointCloud2>();
  m->header.stamp.fromSec(t);
  return m;
}

}  // namespace

TEST(FrameSynchronizer, MatchesTriplesWithinSlop) {
  std::vector<double> stamps;
  FrameSynchronizer sync(10, 0.05, [&](const auto& i, const auto& m, const auto& c) {
    stamps.push_back(i->header.stamp.toSec());
    EXPECT_NEAR(m->header.stamp.toSec(), i->header.stamp.toSec(), 0.05);
    EXPECT_NEAR(c->header.stamp.toSec(), i->header.stamp.toSec(), 0.05);
  });
  for (int k = 0; k < 10; ++k) {
    const double t = 100.0 + 0.1 * k;
    sync.addImage(image(t));
    sync.addMask(image(t));
    sync.addClusters(cloud(t + 0.02));
  }
  // ApproximateTime emits a set once a later message proves it complete: the last may wait.
  EXPECT_GE(stamps.size(), 9u);
  EXPECT_EQ(sync.triples(), stamps.size());
  EXPECT_DOUBLE_EQ(stamps.front(), 100.0);
}

TEST(FrameSynchronizer, FlushReleasesTheLastSetButNeverASentinel) {
  std::vector<double> stamps;
  FrameSynchronizer sync(10, 0.05, [&](const auto& i, const auto&, const auto&) {
    stamps.push_back(i->header.stamp.toSec());
  });
  for (int k = 0; k < 5; ++k) {
    const double t = 100.0 + 0.1 * k;
    sync.addImage(image(t));
    sync.addMask(image(t));
    sync.addClusters(cloud(t + 0.01));
  }
  sync.addImage(image(200.0));  // an unmatched straggler
  sync.flush();
  ASSERT_EQ(stamps.size(), 5u);
  EXPECT_DOUBLE_EQ(stamps.back(), 100.4);
  sync.addImage(image(300.0));  // ignored after flush
  EXPECT_EQ(sync.triples(), 5u);
}

TEST(FrameSynchronizer, NoMatchBeyondSlop) {
  int calls = 0;
  FrameSynchronizer sync(10, 0.01, [&](const auto&, const auto&, const auto&) { ++calls; });
  for (int k = 0; k < 10; ++k) {
    const double t = 100.0 + 0.1 * k;
    sync.addImage(image(t));
    sync.addMask(image(t));
    sync.addClusters(cloud(t + 0.05));
  }
  EXPECT_EQ(calls, 0);
}

TEST(FrameSynchronizer, RejectsBadSettings) {
  EXPECT_THROW(FrameSynchronizer(1, 0.05, {}), std::invalid_argument);
  EXPECT_THROW(FrameSynchronizer(10, 0.0, {}), std::invalid_argument);
}
