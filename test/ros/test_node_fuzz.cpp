// rostest node_fuzz.test (issue 12): half way through a generated drive (the player pauses
// there, the synchronizer's queues holding the drive's messages), a fixed-seed stream of a few
// thousand malformed messages (encodings, sizes, steps, fields, stamps, frame ids, NaN and Inf,
// huge declared sizes) goes to every input topic and to ~overlay_cloud; then the drive goes on.
// The node must take every message, stay up, keep its warnings throttled, and still calibrate
// the drive to the node_bag.test tolerance. Every malformed message carries at least one defect
// the node must refuse, so none can pass as a valid frame (that would be a wrong pair, not a
// robustness failure).

#include "thermal_lidar_calibration/app/runtime/fault_throttle.hpp"
#include "thermal_lidar_calibration/app/files/result_file.hpp"
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
#include <map>
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
  ASSERT_TRUE(waitFor(kHangGuardS, [] { return g_observed.status_messages > 0; })) << "no ~status";
  ASSERT_TRUE(waitFor(kHangGuardS, [] { return g_observed.player_paused_pairs.has_value(); }))
      << "the drive never reached the pause: " << g_observed.last_status;
  ASSERT_TRUE(waitFor(kHangGuardS, [&] {
    return image_pub.getNumSubscribers() > 0 && mask_pub.getNumSubscribers() > 0 &&
           clusters_pub.getNumSubscribers() > 0 && overlay_cloud_pub.getNumSubscribers() > 0;
  }));

  Fuzzer fuzz(20261125);
  const InputCounts before = inputsTaken();
  InputCounts sent;
  const auto taken = [&] {
    return waitForInputsTaken({before.images + sent.images, before.masks + sent.masks,
                               before.clusters + sent.clusters});
  };
  const ros::WallTime start = ros::WallTime::now();
  std::size_t warnings_before = 0;
  {
    std::lock_guard<std::mutex> lock(g_observed.mutex);
    warnings_before = g_observed.node_warnings.size();
  }
  for (int i = 0; i < kMessages && ros::ok(); ++i) {
    switch (i % 5) {
      case 0: image_pub.publish(fuzz.image()); ++sent.images; break;
      case 1: mask_pub.publish(fuzz.image()); ++sent.masks; break;
      case 2: clusters_pub.publish(fuzz.cloud()); ++sent.clusters; break;
      case 3: overlay_cloud_pub.publish(fuzz.cloud()); break;
      default: info_pub.publish(fuzz.cameraInfo()); break;
    }
    // At most 10 messages per input in flight: the node's queues (30) drop none of them.
    if (i % 50 == 49) ASSERT_TRUE(taken()) << "the node stopped taking messages after " << i + 1;
    if (i % 500 == 499) expectAlive(std::to_string(i + 1) + " malformed messages");
  }
  ASSERT_TRUE(taken()) << "the node did not take the whole stream";
  expectAlive("the whole malformed stream");
  const double fuzz_s = (ros::WallTime::now() - start).toSec();

  // Throttled per kind of fault, one line per kind and period (5 s, 10 s for the overlay) on the
  // node's clock: however long the stream took here, no kind has more lines than its periods
  // allow (+2: a line of the drive's said just before the stream, one more at the end), and the
  // kinds are few, far below one per message.
  std::map<std::string, int> lines_per_kind;
  std::size_t lines = 0;
  {
    std::lock_guard<std::mutex> lock(g_observed.mutex);
    for (std::size_t k = warnings_before; k < g_observed.node_warnings.size(); ++k) {
      std::string w = g_observed.node_warnings[k];
      const std::size_t held_back = w.find(" (and ");
      if (held_back != std::string::npos) w.erase(held_back);
      ++lines_per_kind[tlc::FaultThrottle::kindOf(w)];
      ++lines;
    }
  }
  std::printf("[ fuzz ] %d malformed messages taken in %.1f s: %zu warning lines of %zu kinds from the node\n",
              kMessages, fuzz_s, lines, lines_per_kind.size());
  const int most_per_kind = 3 + static_cast<int>(fuzz_s / 5.0);
  for (const auto& [kind, count] : lines_per_kind) {
    EXPECT_LE(count, most_per_kind) << "not throttled in " << fuzz_s << " s: " << kind << warnings();
  }
  if (kMessages > 0) EXPECT_LT(lines_per_kind.size(), static_cast<std::size_t>(kMessages) / 20) << warnings();
  resumePlayer(sent);

  // And the drive still calibrates to the node_bag.test tolerance.
  ASSERT_TRUE(waitFor(kHangGuardS, [] { return g_observed.last_status.state_name == "done"; }))
      << "not done: " << g_observed.last_status;
  const std::string truth_file = pnh.param<std::string>("truth_file", "");
  const std::string result_file = pnh.param<std::string>("result_file", "");
  ASSERT_TRUE(waitFor(kHangGuardS, [&] { return std::ifstream(result_file).good(); }));
  const tlc::Extrinsic truth = tlc::readExtrinsicFile(truth_file);
  const tlc::Extrinsic result = tlc::readExtrinsicFile(result_file);
  const double rot_deg = tlc::rotationErrorRad(result, truth) * 180.0 / M_PI;
  const double trans_m = tlc::translationErrorM(result, truth);
  std::printf("[ fuzz ] result: rotation error %.4f deg, translation error %.2f cm\n", rot_deg, 100 * trans_m);
  EXPECT_LT(rot_deg, 0.3);
  EXPECT_LT(trans_m, 0.05);
}

int main(int argc, char** argv) { return runNodeTests(argc, argv, "node_fuzz_test"); }
