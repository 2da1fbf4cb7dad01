// PersonDetectionAdapter: the detectors on ROS messages, as the detection nodelets and
// calibrate_bag --detect use them. The detectors' own behaviour is tested in test/detection;
// here: headers, sizes, encodings, labels, the input flip and errors that name the topic.

#include "thermal_lidar_calibration/ros/person_detection_adapter.hpp"

#include "thermal_lidar_calibration/ros/msg_conversion.hpp"

#include "../support/lidar_scene.hpp"
#include "../support/thermal_scene.hpp"

#include <boost/make_shared.hpp>
#include <cv_bridge/cv_bridge.h>
#include <gtest/gtest.h>
#include <sensor_msgs/point_cloud2_iterator.h>

#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace tlc = thermal_lidar_calibration;
using tlc::ros_io::PersonDetectionAdapter;
namespace ts = tlc::test_support;

namespace {

// A radiometric 640x512 frame (0.04 K per count) with one person in its upper half.
sensor_msgs::Image::ConstPtr thermalMessage() {
  cv::Mat image = ts::thermalBackground(cv::Size(640, 512), 285.0, 0.05);
  ts::drawPerson(image, 200, 60, 150, 307.0, 301.0);
  std_msgs::Header header;
  header.stamp = ros::Time(1600000001, 250);
  header.frame_id = "thermal_optical";
  return cv_bridge::CvImage(header, "mono16", image).toImageMsg();
}

// The mask pixels' bounding rows.
std::pair<int, int> maskRows(const sensor_msgs::Image& mask) {
  int top = mask.height, bottom = -1;
  for (std::uint32_t v = 0; v < mask.height; ++v) {
    for (std::uint32_t u = 0; u < mask.width; ++u) {
      if (mask.data[v * mask.step + u] != 0) {
        top = std::min<int>(top, v);
        bottom = std::max<int>(bottom, v);
      }
    }
  }
  return {top, bottom};
}

}  // namespace

TEST(PersonDetectionAdapter, MaskHasTheImagesHeaderSizeAndOneId) {
  PersonDetectionAdapter adapter(tlc::DetectionParameters{});
  const auto image = thermalMessage();
  const tlc::ros_io::SegmentedImage seg = adapter.segment(image, "/thermal/image_raw");
  EXPECT_EQ(seg.image, image);  // no flip: the input itself, not a copy
  ASSERT_TRUE(seg.mask);
  EXPECT_EQ(seg.mask->header.stamp, image->header.stamp);
  EXPECT_EQ(seg.mask->header.frame_id, "thermal_optical");
  EXPECT_EQ(seg.mask->width, 640u);
  EXPECT_EQ(seg.mask->height, 512u);
  EXPECT_EQ(seg.mask->encoding, "mono8");
  ASSERT_EQ(seg.segmentation.people.size(), 1u);
  const std::set<std::uint8_t> ids(seg.mask->data.begin(), seg.mask->data.end());
  EXPECT_EQ(ids, (std::set<std::uint8_t>{0, 1}));
  const auto rows = maskRows(*seg.mask);
  EXPECT_NEAR(rows.first, 60, 4);
  EXPECT_NEAR(rows.second, 210, 4);
}

// An upside-down camera: the flip turns the image (and so the mask) before anything else.
TEST(PersonDetectionAdapter, VerticalFlipTurnsImageAndMask) {
  tlc::DetectionParameters params;
  params.input_flip = tlc::detection::ImageFlip::kVertical;
  params.thermal.max_neck_ratio = 0.0;  // the upright person turned over has its neck at the bottom
  PersonDetectionAdapter adapter(params);
  const auto image = thermalMessage();
  const tlc::ros_io::SegmentedImage seg = adapter.segment(image, "/thermal/image_raw");
  ASSERT_NE(seg.image, image);
  EXPECT_EQ(seg.image->header.stamp, image->header.stamp);
  EXPECT_EQ(seg.image->encoding, "mono16");
  const cv::Mat flipped = tlc::ros_io::decodeMonoImage(*seg.image, "t");
  const cv::Mat original = tlc::ros_io::decodeMonoImage(*image, "t");
  EXPECT_EQ(flipped.at<std::uint16_t>(0, 200), original.at<std::uint16_t>(511, 200));
  EXPECT_EQ(flipped.at<std::uint16_t>(511 - 100, 200), original.at<std::uint16_t>(100, 200));
  const auto rows = maskRows(*seg.mask);
  EXPECT_NEAR(rows.first, 511 - 210, 4);
  EXPECT_NEAR(rows.second, 511 - 60, 4);
}

TEST(PersonDetectionAdapter, UnreadableImageNamesTheTopic) {
  PersonDetectionAdapter adapter(tlc::DetectionParameters{});
  auto bad = boost::make_shared<sensor_msgs::Image>(*thermalMessage());
  bad->encoding = "rgb8";
  try {
    adapter.segment(bad, "/FlirA65/image_raw");
    FAIL() << "an rgb8 image was segmented";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("/FlirA65/image_raw"), std::string::npos) << e.what();
  }
}

// Two people on flat ground and a post: the clusters carry the cloud's header, float32 x, y, z,
// a uint32 label per person, and the scan's other fields.
TEST(PersonDetectionAdapter, ClustersHaveTheCloudsHeaderAndUint32Labels) {
  const ts::Terrain flat = ts::Terrain::flat();
  const ts::CraftedScan scan = ts::castScan(
      tlc::synthetic::LidarModel::hdl32e(), flat, ts::Mount{},
      {ts::personAt(flat, 8.0, 1.0, 1), ts::personAt(flat, 12.0, -3.0, 2), ts::postAt(flat, 10.0, 4.0, 1.5, 0.06)},
      0.02, 1);
  std::vector<float> intensity(scan.points.size(), 10.f);
  sensor_msgs::PointCloud2 cloud = tlc::ros_io::encodePointsWithIntensity(scan.points, intensity, "/velodyne", 1600000001.5);
  PersonDetectionAdapter adapter(tlc::DetectionParameters{});
  const tlc::ros_io::DetectedCloud out = adapter.detect(cloud, "/lidar/points");
  ASSERT_TRUE(out.clusters);
  EXPECT_EQ(out.clusters->header.stamp, cloud.header.stamp);
  EXPECT_EQ(out.clusters->header.frame_id, "/velodyne");  // same header; ingest strips the '/'
  ASSERT_EQ(out.clusters->fields.size(), 5u);
  EXPECT_EQ(out.clusters->fields[3].name, "label");
  EXPECT_EQ(out.clusters->fields[3].datatype, sensor_msgs::PointField::UINT32);
  EXPECT_EQ(out.clusters->fields[4].name, "intensity");
  EXPECT_EQ(out.detection.people.size(), 2u);
  std::set<std::uint32_t> labels;
  sensor_msgs::PointCloud2ConstIterator<std::uint32_t> label(*out.clusters, "label");
  for (std::size_t i = 0; i < out.clusters->width; ++i, ++label) labels.insert(*label);
  EXPECT_EQ(labels, (std::set<std::uint32_t>{1, 2}));
  // What the ingest path reads from it: the same points and two people.
  const tlc::ros_io::DecodedClusters decoded = tlc::ros_io::decodeClusters(*out.clusters, "c");
  EXPECT_EQ(decoded.points.size(), out.detection.points.size());
}

// Issue 21: a raw scan with per-point times (velodyne's float32 `time`, and NaN returns as an
// organised driver writes them): every cluster point keeps its own point's time, so the ingest
// path reads the person points' times from the detector's clusters.
TEST(PersonDetectionAdapter, ClusterPointsKeepTheirPointsTimesAndOtherFields) {
  const ts::Terrain flat = ts::Terrain::flat();
  const ts::CraftedScan scan = ts::castScan(tlc::synthetic::LidarModel::hdl32e(), flat, ts::Mount{},
                                            {ts::personAt(flat, 8.0, 1.0, 1), ts::personAt(flat, 12.0, -3.0, 2)}, 0.0, 1);
  sensor_msgs::PointCloud2 cloud;
  cloud.header.stamp = ros::Time(1600000001.5);
  cloud.header.frame_id = "velodyne";
  sensor_msgs::PointCloud2Modifier modifier(cloud);
  modifier.setPointCloud2Fields(5, "x", 1, sensor_msgs::PointField::FLOAT32, "y", 1, sensor_msgs::PointField::FLOAT32,
                                "z", 1, sensor_msgs::PointField::FLOAT32, "ring", 1, sensor_msgs::PointField::UINT16,
                                "time", 1, sensor_msgs::PointField::FLOAT32);
  // Every third point a NaN return: the detector's indices skip them, the copy must not.
  const std::size_t n = scan.points.size() + scan.points.size() / 3;
  modifier.resize(n);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  auto timeOf = [](const Eigen::Vector3f& p) { return -0.1f + 0.1f * (std::atan2(p.y(), p.x()) + 3.2f) / 6.4f; };
  sensor_msgs::PointCloud2Iterator<float> x(cloud, "x"), y(cloud, "y"), z(cloud, "z"), t(cloud, "time");
  sensor_msgs::PointCloud2Iterator<std::uint16_t> ring(cloud, "ring");
  for (std::size_t i = 0, k = 0; i < n; ++i, ++x, ++y, ++z, ++t, ++ring) {
    const bool hole = i % 4 == 3 || k >= scan.points.size();
    const Eigen::Vector3f p = hole ? Eigen::Vector3f(nan, nan, nan) : scan.points[k];
    *x = p.x();
    *y = p.y();
    *z = p.z();
    *t = hole ? -1.0f : timeOf(p);
    *ring = hole ? 0 : scan.ring[k];
    if (!hole) ++k;
  }
  PersonDetectionAdapter adapter(tlc::DetectionParameters{});
  const tlc::ros_io::DetectedCloud out = adapter.detect(cloud, "/lidar/points");
  ASSERT_EQ(out.detection.people.size(), 2u);
  std::vector<std::string> names;
  for (const auto& f : out.clusters->fields) names.push_back(f.name);
  EXPECT_EQ(names, (std::vector<std::string>{"x", "y", "z", "label", "ring", "time"}));
  const tlc::ros_io::DecodedClusters decoded = tlc::ros_io::decodeClusters(*out.clusters, "/lidar/human_clusters");
  ASSERT_EQ(decoded.point_time_s.size(), out.detection.points.size());
  ASSERT_GT(decoded.points.size(), 20u);
  for (std::size_t i = 0; i < decoded.points.size(); ++i) {
    EXPECT_FLOAT_EQ(decoded.point_time_s[i], timeOf(decoded.points[i])) << i;
  }
  sensor_msgs::PointCloud2ConstIterator<std::uint16_t> out_ring(*out.clusters, "ring");
  for (std::size_t i = 0; i < out.clusters->width; ++i, ++out_ring) EXPECT_LT(*out_ring, 32u);
}

TEST(PersonDetectionAdapter, CloudWithoutXYZNamesTheTopic) {
  sensor_msgs::PointCloud2 cloud;
  cloud.width = 1;
  cloud.height = 1;
  cloud.point_step = 4;
  cloud.row_step = 4;
  cloud.data.assign(4, 0);
  PersonDetectionAdapter adapter(tlc::DetectionParameters{});
  try {
    adapter.detect(cloud, "/velodyne_points");
    FAIL() << "a cloud without x, y, z was read";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("/velodyne_points"), std::string::npos) << e.what();
  }
}
