// Per-point capture times in cluster clouds (issue 21): the layouts the velodyne, ouster, hesai
// and livox drivers write, point_time_field auto / none / a name, bad fields, NaN points.

#include "thermal_lidar_calibration/ros/msg_conversion.hpp"
#include "thermal_lidar_calibration/ros/velocity_fields.hpp"

#include "../support/test_files.hpp"

#include <gtest/gtest.h>
#include <sensor_msgs/point_cloud2_iterator.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

namespace tlc = thermal_lidar_calibration;
using sensor_msgs::PointField;
using tlc::PointTimeField;
using tlc::ros_io::decodeClusters;
using tlc::test_support::errorOf;

namespace {

constexpr double kStamp = 1600000000.5;

struct Field {
  std::string name;
  std::uint8_t datatype;
};

std::size_t bytesOf(std::uint8_t datatype) {
  switch (datatype) {
    case PointField::INT8:
    case PointField::UINT8: return 1;
    case PointField::INT16:
    case PointField::UINT16: return 2;
    case PointField::FLOAT64: return 8;
    default: return 4;
  }
}

void write(std::uint8_t* p, std::uint8_t datatype, double v) {
  auto put = [p](auto value) { std::memcpy(p, &value, sizeof(value)); };
  switch (datatype) {
    case PointField::INT8: put(static_cast<std::int8_t>(v)); break;
    case PointField::UINT8: put(static_cast<std::uint8_t>(v)); break;
    case PointField::INT16: put(static_cast<std::int16_t>(v)); break;
    case PointField::UINT16: put(static_cast<std::uint16_t>(v)); break;
    case PointField::INT32: put(static_cast<std::int32_t>(v)); break;
    case PointField::UINT32: put(static_cast<std::uint32_t>(v)); break;
    case PointField::FLOAT32: put(static_cast<float>(v)); break;
    case PointField::FLOAT64: put(v); break;
  }
}

// A cluster cloud laid out as a driver writes it (fields at their natural alignment, the point
// padded to 16 bytes as PCL's aligned point types are), stamped kStamp; values per point in
// field order.
sensor_msgs::PointCloud2 cloud(const std::vector<Field>& fields, const std::vector<std::vector<double>>& values) {
  sensor_msgs::PointCloud2 msg;
  msg.header.frame_id = "lidar";
  msg.header.stamp = ros::Time(kStamp);
  std::uint32_t offset = 0;
  for (const Field& f : fields) {
    const std::uint32_t size = static_cast<std::uint32_t>(bytesOf(f.datatype));
    offset = (offset + size - 1) / size * size;
    PointField pf;
    pf.name = f.name;
    pf.offset = offset;
    pf.datatype = f.datatype;
    pf.count = 1;
    msg.fields.push_back(pf);
    offset += size;
  }
  msg.point_step = (offset + 15) / 16 * 16;
  msg.height = 1;
  msg.width = static_cast<std::uint32_t>(values.size());
  msg.row_step = msg.point_step * msg.width;
  msg.data.assign(msg.row_step, 0);
  for (std::size_t i = 0; i < values.size(); ++i) {
    for (std::size_t k = 0; k < fields.size(); ++k) {
      write(msg.data.data() + i * msg.point_step + msg.fields[k].offset, fields[k].datatype, values[i][k]);
    }
  }
  return msg;
}

const Field kX{"x", PointField::FLOAT32}, kY{"y", PointField::FLOAT32}, kZ{"z", PointField::FLOAT32},
    kIntensity{"intensity", PointField::FLOAT32}, kLabel{"label", PointField::UINT32};

// velodyne_pointcloud's XYZIRT: float32 `time`, seconds relative to the stamp (the last packet's,
// so mostly negative).
sensor_msgs::PointCloud2 velodyneClusters() {
  return cloud({kX, kY, kZ, kIntensity, {"ring", PointField::UINT16}, {"time", PointField::FLOAT32}, kLabel},
               {{10, 1, 0, 20, 5, -0.0712, 1}, {10, 1.1, 0.2, 21, 6, -0.0709, 1}, {12, -2, 0.1, 22, 7, -0.0350, 2}});
}

PointTimeField named(const std::string& name) { return PointTimeField::parse(name); }

// Times are float32 seconds: about 4 ns of resolution at 0.06 s.
void expectTimes(const tlc::ros_io::DecodedClusters& d, const std::vector<double>& expected, double tolerance,
                 const std::string& what) {
  ASSERT_EQ(d.point_time_s.size(), d.points.size()) << what;
  ASSERT_EQ(d.point_time_s.size(), expected.size()) << what;
  for (std::size_t i = 0; i < expected.size(); ++i) EXPECT_NEAR(d.point_time_s[i], expected[i], tolerance) << what << " " << i;
}

}  // namespace

TEST(PointTimes, VelodyneFloatSecondsRelativeToTheStamp) {
  for (const PointTimeField& setting : {PointTimeField{}, named("time")}) {
    expectTimes(decodeClusters(velodyneClusters(), "/c", setting), {-0.0712, -0.0709, -0.0350}, 1e-7, "velodyne");
  }
}

// ouster_ros's PointOS: uint32 `t`, nanoseconds from the stamp (the scan's first measurement).
TEST(PointTimes, OusterUint32NanosecondsRelativeToTheStamp) {
  const auto msg = cloud({kX, kY, kZ, kIntensity, {"t", PointField::UINT32}, {"reflectivity", PointField::UINT16},
                          {"ring", PointField::UINT16}, {"ambient", PointField::UINT16}, {"range", PointField::UINT32},
                          kLabel},
                         {{8, 0, 0, 5, 48123456, 10, 3, 100, 8000, 1}, {8, 0.3, 0, 5, 48170000, 10, 4, 100, 8000, 1}});
  for (const PointTimeField& setting : {PointTimeField{}, named("t")}) {
    expectTimes(decodeClusters(msg, "/c", setting), {0.048123456, 0.04817}, 1e-8, "ouster");
  }
}

// The hesai driver's `timestamp`: float64 absolute seconds, on the stamp's clock.
TEST(PointTimes, HesaiFloat64AbsoluteSecondsBecomeRelativeToTheStamp) {
  const auto msg = cloud({kX, kY, kZ, kIntensity, {"ring", PointField::UINT16}, {"timestamp", PointField::FLOAT64},
                          kLabel},
                         {{9, 1, 0, 7, 2, kStamp + 0.0503, 1}, {9, 1.2, 0, 7, 3, kStamp + 0.0511, 1}});
  // A double near 1.6e9 s resolves 0.24 us.
  for (const PointTimeField& setting : {PointTimeField{}, named("timestamp")}) {
    expectTimes(decodeClusters(msg, "/c", setting), {0.0503, 0.0511}, 1e-6, "hesai");
  }
}

// livox's `offset_time`: uint32 nanoseconds from the stamp.
TEST(PointTimes, LivoxOffsetTimeNanoseconds) {
  const auto msg = cloud({kX, kY, kZ, kIntensity, {"tag", PointField::UINT8}, {"line", PointField::UINT8},
                          {"offset_time", PointField::UINT32}, kLabel},
                         {{15, 2, 0, 30, 0, 2, 61000000, 3}, {15, 2.1, 0, 30, 0, 3, 61250000, 3}});
  for (const PointTimeField& setting : {PointTimeField{}, named("offset_time")}) {
    expectTimes(decodeClusters(msg, "/c", setting), {0.061, 0.06125}, 1e-8, "livox");
  }
}

// Relative or absolute comes from the values against the stamp, not from the name: float64
// relative seconds, and absolute ones under simulated time (a stamp of 100 s).
TEST(PointTimes, RelativeOrAbsoluteIsReadFromTheValues) {
  const auto relative = cloud({kX, kY, kZ, {"timestamp", PointField::FLOAT64}, kLabel}, {{5, 0, 0, -0.02, 1}});
  expectTimes(decodeClusters(relative, "/c"), {-0.02}, 1e-8, "float64 relative");
  auto simulated = cloud({kX, kY, kZ, {"time", PointField::FLOAT64}, kLabel}, {{5, 0, 0, 99.95, 1}, {5, 0, 0, 99.97, 1}});
  simulated.header.stamp = ros::Time(100.0);
  expectTimes(decodeClusters(simulated, "/c"), {-0.05, -0.03}, 1e-9, "absolute, simulated time");
}

TEST(PointTimes, AutoTakesTheFirstKnownNameNoneIgnoresThemANamedFieldMustExist) {
  // Both `time` and `t`: auto takes velodyne's `time`; a name takes that field.
  const auto both = cloud({kX, kY, kZ, {"t", PointField::UINT32}, {"time", PointField::FLOAT32}, kLabel},
                          {{5, 0, 0, 20000000, -0.08, 1}});
  expectTimes(decodeClusters(both, "/c"), {-0.08}, 1e-7, "auto");
  expectTimes(decodeClusters(both, "/c", named("t")), {0.02}, 1e-8, "named t");
  // none: no times, whatever the cloud has; auto without any known name: no times, no error.
  EXPECT_TRUE(decodeClusters(both, "/c", named("none")).point_time_s.empty());
  const auto plain = cloud({kX, kY, kZ, kIntensity, kLabel}, {{5, 0, 0, 1, 1}});
  const auto d = decodeClusters(plain, "/c");
  EXPECT_TRUE(d.point_time_s.empty());
  EXPECT_EQ(d.points.size(), 1u);
  // A named field the cloud lacks is an error naming the topic, the fields and the setting.
  EXPECT_EQ(errorOf([&] { decodeClusters(velodyneClusters(), "/lidar/human_clusters", named("offset_time")); }),
            "/lidar/human_clusters: PointCloud2 has no point time field 'offset_time' (fields: x, y, z, intensity, "
            "ring, time, label); set point_time_field to one of them, auto or none");
}

TEST(PointTimes, AFieldThatCannotHoldTimesIsRefused) {
  EXPECT_EQ(errorOf([&] { decodeClusters(velodyneClusters(), "/c", named("ring")); }),
            "/c: PointCloud2 point time field 'ring' is uint16; times must be float32/float64 seconds or "
            "int32/uint32 nanoseconds (point_time_field: none ignores them)");
  // auto finding a known name of an unusable type says so too, rather than ignoring it.
  const auto narrow = cloud({kX, kY, kZ, {"time", PointField::UINT8}, kLabel}, {{5, 0, 0, 3, 1}});
  EXPECT_NE(errorOf([&] { decodeClusters(narrow, "/c"); }).find("point time field 'time' is uint8"), std::string::npos);
  EXPECT_TRUE(decodeClusters(narrow, "/c", named("none")).point_time_s.empty());
  // A time field outside the point is a corrupt layout.
  auto outside = velodyneClusters();
  outside.fields[5].offset = outside.point_step - 2;
  EXPECT_NE(errorOf([&] { decodeClusters(outside, "/c"); }).find("lies outside point_step"), std::string::npos);
}

// A point dropped for a NaN coordinate or a NaN time takes its time with it: the times left are
// those of the points left, in order.
TEST(PointTimes, NonFinitePointsAndTimesAreDroppedTogether) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto msg = cloud({kX, kY, kZ, {"time", PointField::FLOAT32}, kLabel},
                         {{1, 0, 0, -0.09, 1}, {nan, 0, 0, -0.08, 1}, {3, 0, 0, nan, 1}, {4, 0, 0, -0.06, 2},
                          {5, 0, 0, -0.05, 2}});
  const auto d = decodeClusters(msg, "/c");
  ASSERT_EQ(d.points.size(), 3u);
  EXPECT_EQ(d.nonfinite_dropped, 2u);
  EXPECT_FLOAT_EQ(d.points[1].x(), 4.0f);
  expectTimes(d, {-0.09, -0.06, -0.05}, 1e-7, "after drops");
}

TEST(PointTimes, DecodeFrameCarriesTheTimesAndTheCloudsStamp) {
  sensor_msgs::Image image;
  image.encoding = "mono8";
  image.width = 4;
  image.height = 3;
  image.step = 4;
  image.data.assign(12, 0);
  image.header.stamp = ros::Time(kStamp + 0.004);
  const tlc::Frame f = tlc::ros_io::decodeFrame(image, image, velodyneClusters(), "/i", "/m", "/c");
  EXPECT_DOUBLE_EQ(f.stamp_s, ros::Time(kStamp + 0.004).toSec());
  EXPECT_DOUBLE_EQ(f.cloud_stamp_s, ros::Time(kStamp).toSec());
  ASSERT_EQ(f.point_time_s.size(), 3u);
  EXPECT_NEAR(f.point_time_s[2], -0.035, 1e-7);
  EXPECT_TRUE(tlc::ros_io::decodeFrame(image, image, velodyneClusters(), "/i", "/m", "/c", named("none"))
                  .point_time_s.empty());
}

// The dataset bag keeps each kept pair's people's motion (velocity_fields.hpp): written per point
// from its label, read back by decodeClusters with the times, replaced rather than duplicated when
// written twice; a label without a measured motion reads 0.
TEST(PointTimes, VelocityFieldsRoundTripThroughTheDatasetBagsClusters) {
  tlc::PersonMotion walker;
  walker.label = 1;
  walker.velocity_mps = Eigen::Vector3d(-2.0, 0.5, 0.0);
  walker.std_error_mps = Eigen::Vector3d(0.125, 0.25, 0.5);
  walker.scans = 5;
  tlc::PersonMotion unmeasured;
  unmeasured.label = 2;
  unmeasured.velocity_mps = Eigen::Vector3d(9, 9, 9);
  unmeasured.scans = 1;
  const sensor_msgs::PointCloud2 once =
      tlc::ros_io::withVelocityFields(velodyneClusters(), {walker, unmeasured}, "/clusters");
  const sensor_msgs::PointCloud2 twice = tlc::ros_io::withVelocityFields(once, {walker}, "/clusters");
  EXPECT_EQ(twice.fields.size(), once.fields.size());
  for (const auto& msg : {once, twice}) {
    const auto d = decodeClusters(msg, "/clusters", named("time"));
    expectTimes(d, {-0.0712, -0.0709, -0.0350}, 1e-6, "with velocities");
    ASSERT_EQ(d.point_velocity.size(), 3u);
    EXPECT_EQ(d.point_velocity[0], Eigen::Vector3f(-2.0f, 0.5f, 0.0f));
    EXPECT_EQ(d.point_velocity[1], Eigen::Vector3f(-2.0f, 0.5f, 0.0f));
    EXPECT_EQ(d.point_velocity[2], Eigen::Vector3f::Zero());
    // The velocities' standard errors too (the deskew velocity's: none along z), so a dataset
    // read back judges the timing as the session that kept it (motionFromFields).
    ASSERT_EQ(d.point_velocity_se.size(), 3u);
    EXPECT_EQ(d.point_velocity_se[0], Eigen::Vector2f(0.125f, 0.25f));
    EXPECT_TRUE(std::isnan(d.point_velocity_se[2].x()));
    const std::vector<tlc::PersonMotion> motion =
        tlc::ros_io::motionFromFields(d.labels, d.point_velocity, d.point_velocity_se);
    ASSERT_EQ(motion.size(), 1u);
    EXPECT_EQ(motion[0].label, 1);
    EXPECT_TRUE(motion[0].measured());
    EXPECT_EQ(motion[0].velocity_mps, Eigen::Vector3d(-2.0, 0.5, 0.0));
    EXPECT_EQ(motion[0].std_error_mps, Eigen::Vector3d(0.125, 0.25, 0.0));
  }
  // A dataset bag from before the error fields: velocities without errors, no motion made up.
  sensor_msgs::PointCloud2 old_bag = tlc::ros_io::withVelocityFields(velodyneClusters(), {walker}, "/clusters");
  for (auto& f : old_bag.fields) {
    if (f.name == "vx_se" || f.name == "vy_se") f.name = "unused_" + f.name;
  }
  const auto old_decoded = decodeClusters(old_bag, "/clusters", named("time"));
  EXPECT_EQ(old_decoded.point_velocity.size(), 3u);
  EXPECT_TRUE(old_decoded.point_velocity_se.empty());
  EXPECT_TRUE(tlc::ros_io::motionFromFields(old_decoded.labels, old_decoded.point_velocity,
                                            old_decoded.point_velocity_se)
                  .empty());
  // A cloud without them has no velocities (not zeros that would read as standing still).
  EXPECT_TRUE(decodeClusters(velodyneClusters(), "/clusters").point_velocity.empty());
}
