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

// Stamps from a sensor with an unset or wrong clock: ApproximateTime subtracts stamps and throws
// "Duration is out of dual 32-bit range" when two are more than 2^31 s apart. The synchronizer
// must drop such a message before ApproximateTime sees it, say why, and keep pairing the rest.
TEST(FrameSynchronizer, FarStampsAreDroppedNotThrown) {
  std::vector<double> stamps;
  FrameSynchronizer sync(10, 0.05, [&](const auto& i, const auto&, const auto&) {
    stamps.push_back(i->header.stamp.toSec());
  });
  sync.addImage(image(1600000000.0));
  auto mask = boost::make_shared<sensor_msgs::Image>();
  mask->header.stamp = ros::Time(4294967295u, 0);
  FrameSynchronizer::AddOutcome outcome;
  ASSERT_NO_THROW(outcome = sync.addMask(mask));
  EXPECT_FALSE(outcome.added);
  EXPECT_NE(outcome.fault.find("4294967295"), std::string::npos) << outcome.fault;
  auto zero = boost::make_shared<sensor_msgs::Image>();  // the stamp of an unset clock
  zero->header.stamp = ros::Time(0, 0);
  ASSERT_NO_THROW(sync.addMask(zero));
  auto late = boost::make_shared<sensor_msgs::PointCloud2>();
  late->header.stamp = ros::Time(2200000000u, 0);
  ASSERT_NO_THROW(outcome = sync.addClusters(late));
  EXPECT_FALSE(outcome.added);
  for (int k = 0; k < 10; ++k) {
    const double t = 1600000000.0 + 0.1 * k;
    EXPECT_NO_THROW(sync.addImage(image(t)));
    EXPECT_NO_THROW(sync.addMask(image(t)));
    EXPECT_NO_THROW(sync.addClusters(cloud(t + 0.01)));
  }
  EXPECT_GE(stamps.size(), 9u);
  EXPECT_GE(sync.droppedStamps(), 2u);
}

// One stray message must not decide the time base: when the data keeps arriving in another
// epoch (a first message stamped 0, then the real drive), the synchronizer follows the data.
TEST(FrameSynchronizer, FollowsTheDataWhenTheTimeBaseMoves) {
  std::vector<double> stamps;
  FrameSynchronizer sync(10, 0.05, [&](const auto& i, const auto&, const auto&) {
    stamps.push_back(i->header.stamp.toSec());
  });
  sync.addImage(image(5.0));  // a sensor that has not set its clock yet
  for (int k = 0; k < 30; ++k) {
    const double t = 1600000000.0 + 0.1 * k;
    EXPECT_NO_THROW(sync.addImage(image(t)));
    EXPECT_NO_THROW(sync.addMask(image(t)));
    EXPECT_NO_THROW(sync.addClusters(cloud(t + 0.01)));
  }
  EXPECT_GE(stamps.size(), 20u);
  ASSERT_FALSE(stamps.empty());
  EXPECT_GT(stamps.front(), 1.5e9);
}

// Stamps at the very end of ROS time overflow ros::Time + Duration inside ApproximateTime and
// flush(): refused too.
TEST(FrameSynchronizer, EndOfTimeStampsAreDropped) {
  FrameSynchronizer sync(10, 0.05, [](const auto&, const auto&, const auto&) {});
  auto last = boost::make_shared<sensor_msgs::Image>();
  last->header.stamp = ros::Time(4294967295u, 999999999u);
  FrameSynchronizer::AddOutcome outcome;
  ASSERT_NO_THROW(outcome = sync.addImage(last));
  EXPECT_FALSE(outcome.added);
  auto unset = boost::make_shared<sensor_msgs::Image>();  // stamp 0: a clock not set
  ASSERT_NO_THROW(outcome = sync.addImage(unset));
  EXPECT_FALSE(outcome.added);
  EXPECT_FALSE(sync.dataTime().has_value());
  auto bad_nsec = boost::make_shared<sensor_msgs::Image>();
  bad_nsec->header.stamp.sec = 100;
  bad_nsec->header.stamp.nsec = 4000000000u;  // not normalised: a corrupt header
  ASSERT_NO_THROW(outcome = sync.addImage(bad_nsec));
  EXPECT_FALSE(outcome.added);
  EXPECT_NO_THROW(sync.flush());
}
