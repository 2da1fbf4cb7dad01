// rostest node_fuzz.test (issue 12): while a generated drive plays, a fixed-seed stream of a few
// thousand malformed messages (encodings, sizes, steps, fields, stamps, frame ids, NaN and Inf,
// huge declared sizes) goes to every input topic and to ~overlay_cloud. The node must stay up,
// keep its warnings throttled, and still calibrate the drive to the node_bag.test tolerance.
// Every malformed message carries at least one defect the node must refuse, so none can pass
// as a valid frame (that would be a wrong pair, not a robustness failure).

#include "thermal_lidar_calibration/app/result_file.hpp"
#include "thermal_lidar_calibration/core/extrinsic.hpp"

#include "../support/node_observer.hpp"

#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

using namespace node_observer;
namespace tlc = thermal_lidar_calibration;

namespace {

class Fuzzer {
 public:
  explicit Fuzzer(std::uint64_t seed) : rng_(seed) {}

  template <typename T>
  const T& pick(const std::vector<T>& options) {
    return options[std::uniform_int_distribution<std::size_t>(0, options.size() - 1)(rng_)];
  }
  bool coin(double p = 0.5) { return std::bernoulli_distribution(p)(rng_); }

  ros::Time stamp() {
    const ros::Time now = ros::Time::now();
    switch (std::uniform_int_distribution<int>(0, 5)(rng_)) {
      case 0: return ros::Time(0, 0);
      case 1: return ros::Time(4294967295u, 999999999u);
      case 2: return ros::Time(2200000000u, 0);
      case 3: return now.sec > 1000 ? ros::Time(now.sec - 1000, now.nsec) : now;
      default: return now;  // pairs with the drive's messages: the defect must be the content
    }
  }
  std::string frameId() { return pick<std::string>({"", "/", "thermal_optical", "/velodyne", "a b", std::string(300, 'x')}); }

  // Sizes never 640x512 (the rig's camera), so no image can pass as the drive's.
  sensor_msgs::Image image() {
    sensor_msgs::Image img;
    img.header.stamp = stamp();
    img.header.frame_id = frameId();
    img.encoding = pick<std::string>({"mono8", "mono16", "8UC1", "16UC1", "rgb8", "bgr8", "32FC1", "", "nonsense"});
    img.width = pick<std::uint32_t>({0, 1, 7, 160, 639, 65535, 0xFFFFFFFFu});
    img.height = pick<std::uint32_t>({0, 1, 5, 128, 511, 65535, 0xFFFFFFFFu});
    img.step = pick<std::uint32_t>({0, img.width, img.width * 2u, 3, 0xFFFFFFFFu});
    img.is_bigendian = coin(0.2);
    const std::size_t declared = static_cast<std::size_t>(img.step) * img.height;
    img.data.assign(std::min<std::size_t>(declared, pick<std::size_t>({0, 1, 16, 4096, 200000})), 0x7f);
    return img;
  }

  // A cloud with at least one defect: no label, a duplicate or missing coordinate, fields past
  // the point, declared sizes the data does not hold, a zero step, or a big-endian layout.
  sensor_msgs::PointCloud2 cloud() {
    sensor_msgs::PointCloud2 c;
    c.header.stamp = stamp();
    c.header.frame_id = frameId();
    const int defect = std::uniform_int_distribution<int>(0, 5)(rng_);
    std::vector<std::string> names = {"x", "y", "z", "label"};
    if (defect == 0) names.pop_back();                  // no label
    if (defect == 1) names[1] = "x";                    // x, x, z
    if (defect == 2) names.erase(names.begin() + 2);    // no z
    std::uint32_t offset = 0;
    for (const auto& name : names) {
      sensor_msgs::PointField f;
      f.name = name;
      f.datatype = name == "label" ? pick<std::uint8_t>({1, 2, 3, 4, 5, 6, 7, 8}) : sensor_msgs::PointField::FLOAT32;
      f.count = 1;
      f.offset = offset;
      offset += 4;
      c.fields.push_back(f);
    }
    c.point_step = 16;
    if (defect == 3) c.fields.back().offset = pick<std::uint32_t>({14, 40, 0xFFFFFFF0u});  // past the point
    c.width = pick<std::uint32_t>({1, 10, 1000, 100000000u, 0xFFFFFFFFu});
    c.height = pick<std::uint32_t>({1, 2, 0xFFFFFFFFu});
    c.row_step = c.width * c.point_step;
    std::size_t points = pick<std::size_t>({0, 1, 10, 1000});
    if (defect == 4) c.point_step = pick<std::uint32_t>({0, 3, 0xFFFFFFFFu});  // no room for the fields
    if (defect == 5) c.is_bigendian = true;
    // Declared sizes the data does not hold, unless the defect is elsewhere.
    if (defect < 4 && coin()) points = static_cast<std::size_t>(c.width) * c.height + 1;
    points = std::min<std::size_t>(points, 1000);
    c.data.resize(points * 16);
    const float specials[] = {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
                              -std::numeric_limits<float>::infinity(), 1e38f, 3.0f};
    for (std::size_t i = 0; i + 4 <= c.data.size(); i += 4) {
      const float v = specials[std::uniform_int_distribution<int>(0, 4)(rng_)];
      std::memcpy(&c.data[i], &v, 4);
    }
    return c;
  }

  // Always refused: a zero or NaN focal length, or an unknown model.
  sensor_msgs::CameraInfo cameraInfo() {
    sensor_msgs::CameraInfo info;
    info.header.stamp = stamp();
    info.header.frame_id = frameId();
    info.width = pick<std::uint32_t>({0, 640, 0xFFFFFFFFu});
    info.height = pick<std::uint32_t>({0, 512, 0xFFFFFFFFu});
    info.distortion_model = pick<std::string>({"plumb_bob", "fisheye", "", "rational_polynomial"});
    info.D.assign(pick<std::size_t>({0, 3, 5, 8}), coin() ? std::nan("") : 0.1);
    info.K = {coin() ? 0.0 : std::nan(""), 0, 320, 0, 700, 256, 0, 0, 1};
    return info;
  }

 private:
  std::mt19937_64 rng_;
};

}  // namespace

TEST(NodeFuzz, ThousandsOfMalformedMessagesWhileADrivePlays) {
  ros::NodeHandle nh, pnh("~");
  const int kMessages = pnh.param("messages", 3000);
  auto image_pub = nh.advertise<sensor_msgs::Image>("thermal/image_raw", 100);
  auto mask_pub = nh.advertise<sensor_msgs::Image>("thermal/human_mask", 100);
  auto clusters_pub = nh.advertise<sensor_msgs::PointCloud2>("lidar/human_clusters", 100);
  auto info_pub = nh.advertise<sensor_msgs::CameraInfo>("thermal/camera_info", 100);
  auto overlay_cloud_pub = nh.advertise<sensor_msgs::PointCloud2>("calibration_node/overlay_cloud", 100);
  // Someone watches ~overlay, so the node decodes ~overlay_cloud.
  ros::Subscriber overlay_sub = nh.subscribe("calibration_node/overlay", 10, onOverlay);
  ASSERT_TRUE(waitFor(60.0, [] { return g_observed.status_messages > 0; })) << "no ~status";
  ASSERT_TRUE(waitFor(120.0, [] { return g_observed.last_status.frames_considered > 0; }))
      << "the drive never played: " << g_observed.last_status;

  Fuzzer fuzz(20261125);
  const ros::WallTime start = ros::WallTime::now();
  std::size_t warnings_before = 0;
  {
    std::lock_guard<std::mutex> lock(g_observed.mutex);
    warnings_before = g_observed.node_warnings.size();
  }
  for (int i = 0; i < kMessages && ros::ok(); ++i) {
    switch (i % 5) {
      case 0: image_pub.publish(fuzz.image()); break;
      case 1: mask_pub.publish(fuzz.image()); break;
      case 2: clusters_pub.publish(fuzz.cloud()); break;
      case 3: overlay_cloud_pub.publish(fuzz.cloud()); break;
      default: info_pub.publish(fuzz.cameraInfo()); break;
    }
    ros::WallDuration(0.004).sleep();  // ~250 messages/s beside the drive
    if (i % 500 == 499) expectAlive(std::to_string(i + 1) + " malformed messages");
  }
  const double fuzz_s = (ros::WallTime::now() - start).toSec();
  expectAlive("the whole malformed stream");
  ros::WallDuration(1.0).sleep();
  std::size_t lines = 0;
  {
    std::lock_guard<std::mutex> lock(g_observed.mutex);
    lines = g_observed.node_warnings.size() - warnings_before;
  }
  std::printf("[ fuzz ] %d malformed messages in %.1f s: %zu warning lines from the node\n", kMessages, fuzz_s, lines);
  // Throttled per kind of fault (one line per kind every 5 s): a bounded number of lines however
  // many messages, far below one per message.
  if (kMessages > 0) EXPECT_LT(lines, static_cast<std::size_t>(kMessages) / 20) << warnings();

  // And the drive still calibrates to the node_bag.test tolerance.
  ASSERT_TRUE(waitFor(240.0, [] { return g_observed.last_status.state_name == "done"; }))
      << "not done: " << g_observed.last_status;
  const std::string truth_file = pnh.param<std::string>("truth_file", "");
  const std::string result_file = pnh.param<std::string>("result_file", "");
  ASSERT_TRUE(waitFor(10.0, [&] { return std::ifstream(result_file).good(); }));
  const tlc::Extrinsic truth = tlc::readExtrinsicFile(truth_file);
  const tlc::Extrinsic result = tlc::readExtrinsicFile(result_file);
  const double rot_deg = tlc::rotationErrorRad(result, truth) * 180.0 / M_PI;
  const double trans_m = tlc::translationErrorM(result, truth);
  std::printf("[ fuzz ] result: rotation error %.4f deg, translation error %.2f cm\n", rot_deg, 100 * trans_m);
  EXPECT_LT(rot_deg, 0.3);
  EXPECT_LT(trans_m, 0.05);
}

int main(int argc, char** argv) { return runNodeTests(argc, argv, "node_fuzz_test"); }
