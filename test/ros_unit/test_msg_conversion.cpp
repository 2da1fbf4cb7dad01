// Decoders of ros_io: every supported encoding, label types, NaN points and the error messages.

#include "thermal_lidar_calibration/ros/msg_conversion.hpp"

#include "../support/test_files.hpp"

#include <gtest/gtest.h>
#include <sensor_msgs/image_encodings.h>

#include <cmath>
#include <array>
#include <cstring>
#include <utility>
#include <vector>
#include <limits>

namespace tlc = thermal_lidar_calibration;
using tlc::ros_io::cameraModelFromMsg;
using tlc::ros_io::decodeCloudPoints;
using tlc::ros_io::decodeClusters;
using tlc::ros_io::decodeFrame;
using tlc::ros_io::decodeMonoImage;
using tlc::test_support::errorOf;

namespace {

sensor_msgs::Image makeImage(const std::string& encoding, int width, int height, int bytes,
                             int padding = 0) {
  sensor_msgs::Image msg;
  msg.encoding = encoding;
  msg.width = width;
  msg.height = height;
  msg.step = width * bytes + padding;
  msg.data.assign(static_cast<std::size_t>(msg.step) * height, 0);
  for (int r = 0; r < height; ++r) {
    for (int c = 0; c < width * bytes; ++c) msg.data[r * msg.step + c] = (r * 7 + c) % 251;
  }
  msg.header.frame_id = "thermal_optical";
  msg.header.stamp.fromSec(12.5);
  return msg;
}

struct FieldSpec {
  std::string name;
  std::uint8_t datatype;
};

std::size_t sizeOf(std::uint8_t datatype) {
  switch (datatype) {
    case sensor_msgs::PointField::INT8:
    case sensor_msgs::PointField::UINT8: return 1;
    case sensor_msgs::PointField::INT16:
    case sensor_msgs::PointField::UINT16: return 2;
    case sensor_msgs::PointField::FLOAT64: return 8;
    default: return 4;
  }
}

template <typename T>
void put(std::uint8_t* p, double v) {
  const T t = static_cast<T>(v);
  std::memcpy(p, &t, sizeof(T));
}

void putAs(std::uint8_t* p, std::uint8_t datatype, double v) {
  switch (datatype) {
    case sensor_msgs::PointField::INT8: put<std::int8_t>(p, v); break;
    case sensor_msgs::PointField::UINT8: put<std::uint8_t>(p, v); break;
    case sensor_msgs::PointField::INT16: put<std::int16_t>(p, v); break;
    case sensor_msgs::PointField::UINT16: put<std::uint16_t>(p, v); break;
    case sensor_msgs::PointField::INT32: put<std::int32_t>(p, v); break;
    case sensor_msgs::PointField::UINT32: put<std::uint32_t>(p, v); break;
    case sensor_msgs::PointField::FLOAT32: put<float>(p, v); break;
    case sensor_msgs::PointField::FLOAT64: put<double>(p, v); break;
  }
}

// A cloud with the given fields (packed, then 3 padding bytes) and one row of points.
sensor_msgs::PointCloud2 makeCloud(const std::vector<FieldSpec>& fields,
                                   const std::vector<std::vector<double>>& points) {
  sensor_msgs::PointCloud2 msg;
  msg.header.frame_id = "velodyne";
  std::uint32_t offset = 0;
  for (const auto& f : fields) {
    sensor_msgs::PointField pf;
    pf.name = f.name;
    pf.offset = offset;
    pf.datatype = f.datatype;
    pf.count = 1;
    msg.fields.push_back(pf);
    offset += sizeOf(f.datatype);
  }
  msg.point_step = offset + 3;
  msg.height = 1;
  msg.width = points.size();
  msg.row_step = msg.point_step * msg.width;
  msg.is_dense = false;
  msg.data.assign(msg.row_step, 0);
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (std::size_t k = 0; k < fields.size(); ++k) {
      putAs(msg.data.data() + i * msg.point_step + msg.fields[k].offset, fields[k].datatype,
            points[i][k]);
    }
  }
  return msg;
}

sensor_msgs::PointCloud2 xyzLabelCloud(std::uint8_t label_type) {
  return makeCloud({{"x", sensor_msgs::PointField::FLOAT32},
                    {"y", sensor_msgs::PointField::FLOAT32},
                    {"z", sensor_msgs::PointField::FLOAT32},
                    {"label", label_type}},
                   {{1.0, 2.0, 3.0, 1}, {-1.5, 0.25, 8.0, 2}, {0.0, 0.0, 1.0, 2}});
}

sensor_msgs::CameraInfo goodInfo() {
  sensor_msgs::CameraInfo info;
  info.width = 640;
  info.height = 512;
  info.distortion_model = "plumb_bob";
  info.D = {-0.0496, 0.3632, 0, 0, 0};
  info.K = {772.41, 0, 322.67, 0, 772.83, 250.66, 0, 0, 1};
  return info;
}

}  // namespace

TEST(DecodeMonoImage, EveryEightBitEncoding) {
  for (const std::string enc : {"mono8", "8UC1"}) {
    const sensor_msgs::Image msg = makeImage(enc, 5, 4, 1);
    const cv::Mat m = decodeMonoImage(msg, "/t");
    ASSERT_EQ(m.type(), CV_8UC1) << enc;
    EXPECT_EQ(m.cols, 5);
    EXPECT_EQ(m.rows, 4);
    EXPECT_EQ(m.at<std::uint8_t>(2, 3), msg.data[2 * msg.step + 3]);
  }
}

TEST(DecodeMonoImage, EverySixteenBitEncoding) {
  for (const std::string enc : {"mono16", "16UC1"}) {
    const sensor_msgs::Image msg = makeImage(enc, 5, 4, 2);
    const cv::Mat m = decodeMonoImage(msg, "/t");
    ASSERT_EQ(m.type(), CV_16UC1) << enc;
    std::uint16_t expected;
    std::memcpy(&expected, &msg.data[3 * msg.step + 2 * 4], 2);
    EXPECT_EQ(m.at<std::uint16_t>(3, 4), expected);
  }
}

TEST(DecodeMonoImage, RowPaddingIsSkipped) {
  const sensor_msgs::Image msg = makeImage("mono8", 5, 3, 1, 3);
  const cv::Mat m = decodeMonoImage(msg, "/t");
  EXPECT_EQ(m.at<std::uint8_t>(2, 4), msg.data[2 * msg.step + 4]);
}

TEST(DecodeMonoImage, DeepCopy) {
  sensor_msgs::Image msg = makeImage("mono8", 4, 4, 1);
  const cv::Mat m = decodeMonoImage(msg, "/t");
  const auto before = m.at<std::uint8_t>(1, 1);
  msg.data[msg.step + 1] ^= 0xFF;
  EXPECT_EQ(m.at<std::uint8_t>(1, 1), before);
}

TEST(DecodeMonoImage, ColourEncodingsAreRejectedNamingTheTopic) {
  for (const std::string enc : {"rgb8", "bgr8", "rgba8", "32FC1", "8UC3", "bayer_rggb8"}) {
    const sensor_msgs::Image msg = makeImage(enc, 4, 4, 3);
    const std::string e = errorOf([&] { decodeMonoImage(msg, "/thermal/human_mask"); });
    EXPECT_NE(e.find("/thermal/human_mask: image encoding '" + enc + "' is not supported"),
              std::string::npos)
        << e;
    EXPECT_NE(e.find("mono8"), std::string::npos) << e;
    EXPECT_EQ(e.find('\n'), std::string::npos);
  }
}

TEST(DecodeMonoImage, BadLayoutsAreErrors) {
  sensor_msgs::Image truncated = makeImage("mono8", 8, 8, 1);
  truncated.data.resize(20);
  EXPECT_NE(errorOf([&] { decodeMonoImage(truncated, "/i"); }).find("truncated"),
            std::string::npos);
  sensor_msgs::Image small_step = makeImage("mono16", 8, 8, 2);
  small_step.step = 8;
  EXPECT_NE(errorOf([&] { decodeMonoImage(small_step, "/i"); }).find("step"), std::string::npos);
  sensor_msgs::Image big_endian = makeImage("mono16", 8, 8, 2);
  big_endian.is_bigendian = 1;
  EXPECT_NE(errorOf([&] { decodeMonoImage(big_endian, "/i"); }).find("big-endian"),
            std::string::npos);
  sensor_msgs::Image empty = makeImage("mono8", 0, 0, 1);
  EXPECT_NE(errorOf([&] { decodeMonoImage(empty, "/i"); }).find("empty"), std::string::npos);
}

TEST(DecodeClusters, EveryLabelType) {
  for (std::uint8_t type :
       {sensor_msgs::PointField::INT8, sensor_msgs::PointField::UINT8,
        sensor_msgs::PointField::INT16, sensor_msgs::PointField::UINT16,
        sensor_msgs::PointField::INT32, sensor_msgs::PointField::UINT32,
        sensor_msgs::PointField::FLOAT32}) {
    const auto d = decodeClusters(xyzLabelCloud(type), "/c");
    ASSERT_EQ(d.points.size(), 3u) << int(type);
    ASSERT_EQ(d.labels.size(), 3u);
    EXPECT_EQ(d.labels[0], 1);
    EXPECT_EQ(d.labels[1], 2);
    EXPECT_FLOAT_EQ(d.points[1].x(), -1.5f);
    EXPECT_FLOAT_EQ(d.points[1].y(), 0.25f);
    EXPECT_FLOAT_EQ(d.points[1].z(), 8.0f);
    EXPECT_EQ(d.nonfinite_dropped, 0u);
  }
}

TEST(DecodeClusters, Float64CoordinatesAreConverted) {
  const auto msg = makeCloud({{"label", sensor_msgs::PointField::UINT16},
                              {"x", sensor_msgs::PointField::FLOAT64},
                              {"y", sensor_msgs::PointField::FLOAT64},
                              {"z", sensor_msgs::PointField::FLOAT64}},
                             {{7, 0.5, -0.5, 4.0}});
  const auto d = decodeClusters(msg, "/c");
  ASSERT_EQ(d.points.size(), 1u);
  EXPECT_EQ(d.labels[0], 7);
  EXPECT_FLOAT_EQ(d.points[0].z(), 4.0f);
}

TEST(DecodeClusters, MissingLabelNamesTopicAndFields) {
  const auto msg = makeCloud({{"x", sensor_msgs::PointField::FLOAT32},
                              {"y", sensor_msgs::PointField::FLOAT32},
                              {"z", sensor_msgs::PointField::FLOAT32},
                              {"intensity", sensor_msgs::PointField::FLOAT32}},
                             {{1, 2, 3, 4}});
  EXPECT_EQ(errorOf([&] { decodeClusters(msg, "/lidar/human_clusters"); }),
            "/lidar/human_clusters: PointCloud2 has no 'label' field (fields: x, y, z, "
            "intensity); publish one integer label per person");
}

TEST(DecodeClusters, NonFinitePointsAreDroppedAndCounted) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const auto msg = makeCloud({{"x", sensor_msgs::PointField::FLOAT32},
                              {"y", sensor_msgs::PointField::FLOAT32},
                              {"z", sensor_msgs::PointField::FLOAT32},
                              {"label", sensor_msgs::PointField::INT32}},
                             {{nan, 1, 1, 1}, {1, 1, 5, 1}, {1, inf, 1, 1}, {1, 1, -inf, 2},
                              {2, 2, 6, 2}});
  const auto d = decodeClusters(msg, "/c");
  EXPECT_EQ(d.points.size(), 2u);
  EXPECT_EQ(d.labels.size(), 2u);
  EXPECT_EQ(d.nonfinite_dropped, 3u);
  EXPECT_FLOAT_EQ(d.points[1].z(), 6.0f);
}

TEST(DecodeClusters, BadLayoutsAreErrors) {
  auto int_x = makeCloud({{"x", sensor_msgs::PointField::INT16},
                          {"y", sensor_msgs::PointField::FLOAT32},
                          {"z", sensor_msgs::PointField::FLOAT32},
                          {"label", sensor_msgs::PointField::INT32}},
                         {{1, 2, 3, 4}});
  EXPECT_NE(errorOf([&] { decodeClusters(int_x, "/c"); }).find("field 'x' is int16"),
            std::string::npos);
  auto no_z = makeCloud({{"x", sensor_msgs::PointField::FLOAT32},
                         {"y", sensor_msgs::PointField::FLOAT32},
                         {"label", sensor_msgs::PointField::INT32}},
                        {{1, 2, 3}});
  EXPECT_NE(errorOf([&] { decodeClusters(no_z, "/c"); }).find("no 'z' field"), std::string::npos);
  auto big = xyzLabelCloud(sensor_msgs::PointField::INT32);
  big.is_bigendian = true;
  EXPECT_NE(errorOf([&] { decodeClusters(big, "/c"); }).find("big-endian"), std::string::npos);
  auto truncated = xyzLabelCloud(sensor_msgs::PointField::INT32);
  truncated.data.resize(5);
  EXPECT_NE(errorOf([&] { decodeClusters(truncated, "/c"); }).find("truncated"),
            std::string::npos);
  auto outside = xyzLabelCloud(sensor_msgs::PointField::INT32);
  outside.fields[3].offset = 100;
  EXPECT_NE(errorOf([&] { decodeClusters(outside, "/c"); }).find("outside point_step"),
            std::string::npos);
  auto fractional = makeCloud({{"x", sensor_msgs::PointField::FLOAT32},
                               {"y", sensor_msgs::PointField::FLOAT32},
                               {"z", sensor_msgs::PointField::FLOAT32},
                               {"label", sensor_msgs::PointField::FLOAT32}},
                              {{1, 2, 3, 1.5}});
  EXPECT_NE(errorOf([&] { decodeClusters(fractional, "/c"); }).find("not an int32 integer"),
            std::string::npos);
}

TEST(DecodeClusters, EmptyCloudIsEmpty) {
  const auto msg = makeCloud({{"x", sensor_msgs::PointField::FLOAT32},
                              {"y", sensor_msgs::PointField::FLOAT32},
                              {"z", sensor_msgs::PointField::FLOAT32},
                              {"label", sensor_msgs::PointField::INT32}},
                             {});
  EXPECT_TRUE(decodeClusters(msg, "/c").points.empty());
}

// ~overlay_cloud once ran without these checks: a declared 2^32-1 x 2^32-1 cloud with 16 bytes
// of data spun for hours, width 1e8 read out of bounds, fields x, x, z ended the node.
TEST(DecodeCloudPoints, DeclaredSizesTheDataDoesNotHoldAreErrors) {
  auto cloud = makeCloud({{"x", sensor_msgs::PointField::FLOAT32},
                          {"y", sensor_msgs::PointField::FLOAT32},
                          {"z", sensor_msgs::PointField::FLOAT32}},
                         {{1, 2, 3}});
  cloud.point_step = 16;
  cloud.data.assign(16, 0);
  for (const auto& wh : std::vector<std::pair<std::uint32_t, std::uint32_t>>{
           {0xFFFFFFFFu, 0xFFFFFFFFu}, {100000000u, 1u}, {1u, 0xFFFFFFFFu}}) {
    auto huge = cloud;
    huge.width = wh.first;
    huge.height = wh.second;
    huge.row_step = huge.width * huge.point_step;  // wraps in uint32, as a hostile sender would
    const std::string error = errorOf([&] { decodeCloudPoints(huge, "/c", 1000); });
    EXPECT_TRUE(error.find("truncated") != std::string::npos ||
                error.find("more than memory") != std::string::npos ||
                error.find("row_step") != std::string::npos)
        << wh.first << " x " << wh.second << ": " << error;
    EXPECT_EQ(error.rfind("/c: ", 0), 0u) << error;
  }
  // Every declared size at its maximum: the products are computed in 64 bits, checked.
  auto largest = cloud;
  largest.width = largest.height = largest.point_step = largest.row_step = 0xFFFFFFFFu;
  EXPECT_NE(errorOf([&] { decodeCloudPoints(largest, "/c", 1000); }).find("row_step"),
            std::string::npos);
}

TEST(DecodeCloudPoints, EveryCloudIsCheckedLikeTheClusters) {
  const auto no_y = makeCloud({{"x", sensor_msgs::PointField::FLOAT32},
                               {"x", sensor_msgs::PointField::FLOAT32},
                               {"z", sensor_msgs::PointField::FLOAT32}},
                              {{1, 2, 3}});
  EXPECT_NE(errorOf([&] { decodeCloudPoints(no_y, "/c", 1000); }).find("no 'y' field"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { decodeClusters(no_y, "/c"); }).find("no 'y' field"), std::string::npos);
  auto outside = xyzLabelCloud(sensor_msgs::PointField::INT32);
  outside.fields[1].offset = 1000;
  EXPECT_NE(errorOf([&] { decodeCloudPoints(outside, "/c", 1000); }).find("outside point_step"),
            std::string::npos);
  auto big = xyzLabelCloud(sensor_msgs::PointField::INT32);
  big.is_bigendian = true;
  EXPECT_NE(errorOf([&] { decodeCloudPoints(big, "/c", 1000); }).find("big-endian"),
            std::string::npos);
}

TEST(DecodeCloudPoints, ReadsAtMostAboutMaxPointsAndSkipsRowPadding) {
  std::vector<std::vector<double>> points;
  for (int i = 0; i < 1000; ++i) points.push_back({double(i), 0.0, 1.0, 7});
  points[10][0] = std::numeric_limits<double>::quiet_NaN();
  auto cloud = makeCloud({{"x", sensor_msgs::PointField::FLOAT32},
                          {"y", sensor_msgs::PointField::FLOAT32},
                          {"z", sensor_msgs::PointField::FLOAT32},
                          {"intensity", sensor_msgs::PointField::FLOAT32}},
                         points);
  EXPECT_EQ(decodeCloudPoints(cloud, "/c", 5000).size(), 999u);  // NaN dropped
  const auto every_tenth = decodeCloudPoints(cloud, "/c", 100);
  ASSERT_EQ(every_tenth.size(), 99u);  // point 10 is NaN
  EXPECT_FLOAT_EQ(every_tenth[1].x(), 20.0f);
  // Two rows of 500 with 8 bytes of padding after each row.
  sensor_msgs::PointCloud2 padded = cloud;
  padded.width = 500;
  padded.height = 2;
  padded.row_step = 500 * cloud.point_step + 8;
  padded.data.assign(static_cast<std::size_t>(padded.row_step) * 2, 0);
  for (int r = 0; r < 2; ++r) {
    std::memcpy(&padded.data[r * padded.row_step], &cloud.data[r * 500 * cloud.point_step],
                500 * cloud.point_step);
  }
  const auto all = decodeCloudPoints(padded, "/c", 5000);
  ASSERT_EQ(all.size(), 999u);
  EXPECT_FLOAT_EQ(all.back().x(), 999.0f);
}

TEST(DecodeMonoImage, HugeDeclaredSizesAreErrorsNotAllocations) {
  sensor_msgs::Image msg = makeImage("mono8", 4, 4, 1);
  for (const auto& whs : std::vector<std::array<std::uint32_t, 3>>{
           {0xFFFFFFFFu, 1u, 0xFFFFFFFFu}, {1u, 0xFFFFFFFFu, 1u}, {70000u, 70000u, 70000u},
           {4u, 0xFFFFFFFFu, 0xFFFFFFFFu}}) {
    sensor_msgs::Image huge = msg;
    huge.width = whs[0];
    huge.height = whs[1];
    huge.step = whs[2];
    const std::string error = errorOf([&] { decodeMonoImage(huge, "/t"); });
    EXPECT_EQ(error.rfind("/t: ", 0), 0u) << error;
  }
}

TEST(CameraModelFromMsg, GoodPlumbBob) {
  const tlc::CameraModel m = cameraModelFromMsg(goodInfo());
  EXPECT_EQ(m.width, 640);
  EXPECT_EQ(m.height, 512);
  EXPECT_DOUBLE_EQ(m.fx, 772.41);
  EXPECT_DOUBLE_EQ(m.cy, 250.66);
  EXPECT_DOUBLE_EQ(m.distortion[1], 0.3632);
  EXPECT_TRUE(m.hasDistortion());
}

TEST(CameraModelFromMsg, NoDistortion) {
  auto info = goodInfo();
  info.D.clear();
  info.distortion_model = "";
  EXPECT_FALSE(cameraModelFromMsg(info).hasDistortion());
  info.distortion_model = "rational_polynomial";
  info.D.assign(8, 0.0);
  EXPECT_FALSE(cameraModelFromMsg(info).hasDistortion());
}

TEST(CameraModelFromMsg, BadInfoIsAnError) {
  auto zero_k = goodInfo();
  zero_k.K.fill(0.0);
  EXPECT_NE(errorOf([&] { cameraModelFromMsg(zero_k); }).find("K is all zeros"),
            std::string::npos);
  auto no_size = goodInfo();
  no_size.width = 0;
  EXPECT_NE(errorOf([&] { cameraModelFromMsg(no_size); }).find("image size"), std::string::npos);
  auto fisheye = goodInfo();
  fisheye.distortion_model = "equidistant";
  fisheye.D = {0.1, 0.01, 0, 0};
  EXPECT_NE(errorOf([&] { cameraModelFromMsg(fisheye); }).find("not supported"),
            std::string::npos);
  auto four = goodInfo();
  four.D = {0.1, 0.2, 0.0, 0.0};
  EXPECT_NE(errorOf([&] { cameraModelFromMsg(four); }).find("5 distortion coefficients"),
            std::string::npos);
}

TEST(DecodeFrame, CombinesTheThreeMessages) {
  const auto image = makeImage("mono16", 6, 4, 2);
  auto mask = makeImage("mono8", 6, 4, 1);
  const auto cloud = xyzLabelCloud(sensor_msgs::PointField::UINT8);
  const tlc::Frame f = decodeFrame(image, mask, cloud, "/i", "/m", "/c");
  EXPECT_DOUBLE_EQ(f.stamp_s, 12.5);
  EXPECT_EQ(f.camera_frame, "thermal_optical");
  EXPECT_EQ(f.lidar_frame, "velodyne");
  EXPECT_EQ(f.image.type(), CV_16UC1);
  EXPECT_EQ(f.mask.type(), CV_8UC1);
  EXPECT_EQ(f.points.size(), 3u);
  EXPECT_EQ(f.labels.size(), 3u);

  auto wrong_size = makeImage("mono8", 5, 4, 1);
  EXPECT_NE(errorOf([&] { decodeFrame(image, wrong_size, cloud, "/i", "/m", "/c"); })
                .find("/m: mask is 5x4 but the image on /i is 6x4"),
            std::string::npos);
  auto rgb_mask = makeImage("rgb8", 6, 4, 3);
  EXPECT_NE(errorOf([&] { decodeFrame(image, rgb_mask, cloud, "/i", "/m", "/c"); })
                .find("/m: image encoding 'rgb8'"),
            std::string::npos);
}

// FieldSAFE writes tf1-style ids ("/velodyne"); tf2 rejects them and they name the same sensor.
TEST(MsgConversion, FrameIdsLoseTheirLeadingSlash) {
  EXPECT_EQ(tlc::ros_io::tfFrameId("/velodyne"), "velodyne");
  EXPECT_EQ(tlc::ros_io::tfFrameId("//thermal_optical"), "thermal_optical");
  EXPECT_EQ(tlc::ros_io::tfFrameId("base_link/velodyne"), "base_link/velodyne");
  EXPECT_EQ(tlc::ros_io::tfFrameId("/"), "");
  EXPECT_EQ(tlc::ros_io::tfFrameId(""), "");
}
