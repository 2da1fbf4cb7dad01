// rostests node_hostile.test (NodeHostile.*) and node_disk_full.test (NodeDiskFull.*): hostile
// input to a running calibration_node while a generated bag plays. Each case publishes what once
// ended or hung the node, then checks that the node is still there (its ~status keeps coming, its
// services answer) and that it said what was wrong. The cases run in order: the stamp cases while
// the player is paused half way through the drive (node_hostile.test: --pause-after-pairs), the
// overlay cases once the node has a result. Each waits for the node's own account of what it
// received (~status counts, the overlay it draws), never for a time.

#include <thermal_lidar_calibration/CalibrationStatus.h>

#include <diagnostic_msgs/DiagnosticArray.h>
#include "../support/node_observer.hpp"

#include <gtest/gtest.h>
#include <ros/ros.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <rosgraph_msgs/Log.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>
#include <std_srvs/Trigger.h>

#include <sys/stat.h>
#include <unistd.h>
#include <xmlrpcpp/XmlRpc.h>

#include <atomic>
#include <cmath>
#include <functional>
#include <iostream>
#include <map>
#include <mutex>
#include <string>
#include <vector>

using thermal_lidar_calibration::CalibrationStatus;

using namespace node_observer;

namespace {

sensor_msgs::Image monoImage(const ros::Time& stamp, int width, int height) {
  sensor_msgs::Image img;
  img.header.stamp = stamp;
  img.header.frame_id = "thermal_optical";
  img.width = width;
  img.height = height;
  img.encoding = "mono8";
  img.step = static_cast<std::uint32_t>(width);
  img.data.assign(static_cast<std::size_t>(img.step) * height, 0);
  return img;
}

sensor_msgs::PointCloud2 cloudHeader(const ros::Time& stamp) {
  sensor_msgs::PointCloud2 c;
  c.header.stamp = stamp;
  c.header.frame_id = "velodyne";
  return c;
}

// The nodes the ROS master lists as subscribers of `topic` (registered: a node subscribes
// there in the same call that makes its subscriber, before any connection).
std::vector<std::string> subscribersOf(const std::string& topic) {
  XmlRpc::XmlRpcValue args, result, payload;
  args[0] = ros::this_node::getName();
  EXPECT_TRUE(ros::master::execute("getSystemState", args, result, payload, true));
  std::vector<std::string> nodes;
  for (int i = 0; i < payload[1].size(); ++i) {
    if (static_cast<std::string>(payload[1][i][0]) != topic) continue;
    for (int j = 0; j < payload[1][i][1].size(); ++j) nodes.push_back(payload[1][i][1][j]);
  }
  return nodes;
}

// x, y, z float32 points of a 20 x 10 grid 6 m in front of the camera, in the LiDAR frame,
// through T_lidar_camera (the node's result on /tf_static): drawn on ~overlay when decoded.
sensor_msgs::PointCloud2 cloudInView(const geometry_msgs::Transform& T_lidar_camera) {
  sensor_msgs::PointCloud2 c = cloudHeader(ros::Time::now());
  sensor_msgs::PointField f;
  f.datatype = sensor_msgs::PointField::FLOAT32;
  f.count = 1;
  for (const char* name : {"x", "y", "z"}) {
    f.name = name;
    c.fields.push_back(f);
    f.offset += 4;
  }
  c.point_step = 12;
  c.height = 1;
  c.width = 200;
  c.row_step = c.width * c.point_step;
  const auto& q = T_lidar_camera.rotation;
  const auto& t = T_lidar_camera.translation;
  for (int i = 0; i < 200; ++i) {
    const double p[3] = {-1.0 + 0.1 * (i % 20), -0.5 + 0.1 * (i / 20), 6.0};
    // v' = v + 2 w (u x v) + 2 u x (u x v), u = (x, y, z) of the unit quaternion
    const double u[3] = {q.x, q.y, q.z};
    const double uv[3] = {u[1] * p[2] - u[2] * p[1], u[2] * p[0] - u[0] * p[2], u[0] * p[1] - u[1] * p[0]};
    const double uuv[3] = {u[1] * uv[2] - u[2] * uv[1], u[2] * uv[0] - u[0] * uv[2], u[0] * uv[1] - u[1] * uv[0]};
    const float out[3] = {static_cast<float>(p[0] + 2 * (q.w * uv[0] + uuv[0]) + t.x),
                          static_cast<float>(p[1] + 2 * (q.w * uv[1] + uuv[1]) + t.y),
                          static_cast<float>(p[2] + 2 * (q.w * uv[2] + uuv[2]) + t.z)};
    const auto* bytes = reinterpret_cast<const std::uint8_t*>(out);
    c.data.insert(c.data.end(), bytes, bytes + sizeof(out));
  }
  return c;
}

// The latest ~overlay image, by the stamp of the thermal image it was drawn on.
struct Overlays {
  std::mutex mutex;
  std::map<ros::Time, std::vector<std::uint8_t>> by_stamp;
};
Overlays g_overlays;

void onOverlayImage(const sensor_msgs::Image::ConstPtr& msg) {
  std::lock_guard<std::mutex> lock(g_overlays.mutex);
  g_overlays.by_stamp[msg->header.stamp] = msg->data;
}

}  // namespace

// A stamp from a sensor with an unset clock (0) or a corrupt one (4294967295, 2.2e9) beside the
// drive's stamps: ApproximateTime threw "Duration is out of dual 32-bit range" out of the
// callback and the node exited. Now each is dropped with a warning naming topic and stamp.
TEST(NodeHostile, FarApartStampsDoNotEndTheNode) {
  ros::NodeHandle nh;
  auto image_pub = nh.advertise<sensor_msgs::Image>("thermal/image_raw", 10);
  auto mask_pub = nh.advertise<sensor_msgs::Image>("thermal/human_mask", 10);
  auto cloud_pub = nh.advertise<sensor_msgs::PointCloud2>("lidar/human_clusters", 10);
  ASSERT_TRUE(waitFor(kHangGuardS, [] { return g_observed.status_messages > 0; })) << "no ~status";
  ASSERT_TRUE(waitFor(kHangGuardS, [&] {
    return image_pub.getNumSubscribers() > 0 && mask_pub.getNumSubscribers() > 0 &&
           cloud_pub.getNumSubscribers() > 0;
  }));
  // Half way through the drive (its stamps near 1.6e9 fill the synchronizer's queues), the
  // player waits while this case sends one message at a time, each taken by the node before the
  // next: a stamp more than 2^31 s from the drive's, a stamp 0 followed by one at 2.2e9.
  ASSERT_TRUE(waitFor(kHangGuardS, [] { return g_observed.player_paused_pairs.has_value(); }))
      << "the player never paused: " << g_observed.last_status;
  EXPECT_GT(*g_observed.player_paused_pairs, 0u);
  const InputCounts before = inputsTaken();
  InputCounts sent;
  const auto taken = [&] {
    return waitForInputsTaken({before.images + sent.images, before.masks + sent.masks,
                               before.clusters + sent.clusters});
  };
  mask_pub.publish(monoImage(ros::Time(4294967295u, 0), 640, 512));
  ++sent.masks;
  EXPECT_TRUE(taken());
  image_pub.publish(monoImage(ros::Time(0, 0), 640, 512));
  ++sent.images;
  EXPECT_TRUE(taken());
  cloud_pub.publish(cloudHeader(ros::Time(2200000000u, 0)));
  ++sent.clusters;
  EXPECT_TRUE(taken());
  cloud_pub.publish(cloudHeader(ros::Time(4294967295u, 0)));
  ++sent.clusters;
  EXPECT_TRUE(taken());
  expectAlive("messages with far-apart stamps");
  EXPECT_TRUE(waitFor(kHangGuardS, said({"/thermal/human_mask", "4294967295"}))) << warnings();
  resumePlayer(sent);  // the drive goes on to its result (the next cases need it)
}

// ~overlay_cloud once a result exists (the overlay then decodes the full cloud): a declared
// 2^32-1 x 2^32-1 cloud with 16 bytes spun the callback thread at 100 % (~status and ~save
// stopped), width 1e8 with 16 bytes segfaulted, fields x, x, z (no y) ended the node. Each is
// now refused by the ingest path's cloud check, and the overlay keeps coming.
// A full cloud at 10 Hz costs its deserialization even when nobody looks (issue 10): the node
// subscribes ~overlay_cloud only while someone watches ~overlay.
TEST(NodeHostile, OverlayCloudIsSubscribedOnlyWhileOverlayIsWatched) {
  ros::NodeHandle nh;
  auto cloud_pub = nh.advertise<sensor_msgs::PointCloud2>("calibration_node/overlay_cloud", 1);
  ASSERT_TRUE(waitFor(kHangGuardS, [] { return g_observed.status_messages > 0; })) << "no ~status";
  // The node is up, so a subscription made at its start would be registered by now.
  EXPECT_TRUE(subscribersOf("/calibration_node/overlay_cloud").empty())
      << "~overlay_cloud subscribed with nobody watching";
  {
    ros::Subscriber overlay_sub = nh.subscribe("calibration_node/overlay", 1, onOverlay);
    EXPECT_TRUE(waitFor(kHangGuardS, [&] { return cloud_pub.getNumSubscribers() > 0; }))
        << "~overlay_cloud not subscribed while ~overlay is watched";
  }
  EXPECT_TRUE(waitFor(kHangGuardS, [&] { return cloud_pub.getNumSubscribers() == 0; }))
      << "~overlay_cloud still subscribed after the last ~overlay subscriber left";
  EXPECT_TRUE(subscribersOf("/calibration_node/overlay_cloud").empty());
}

// Each malformed cloud is shown to reach the overlay: a valid cloud in view is drawn first (the
// overlay changes), then the malformed one replaces it and the overlay is drawn without it
// (back to the overlay without a cloud). A cloud that had not arrived yet would leave the valid
// one drawn, so the case cannot pass without the malformed cloud decoded.
TEST(NodeHostile, MalformedOverlayCloudAfterTheResult) {
  ASSERT_TRUE(waitFor(kHangGuardS, [] { return g_observed.last_status.state_name == "done"; }))
      << "no result: " << g_observed.last_status;
  geometry_msgs::Transform T_lidar_camera;
  {
    std::lock_guard<std::mutex> lock(g_observed.mutex);
    const auto result = g_observed.tf_static.find(g_observed.last_status.child_frame);
    ASSERT_NE(result, g_observed.tf_static.end()) << "no result on /tf_static";
    T_lidar_camera = result->second.second.transform;
  }
  ros::NodeHandle nh;
  ros::Subscriber overlay_sub = nh.subscribe("calibration_node/overlay", 10, onOverlayImage);
  auto image_pub = nh.advertise<sensor_msgs::Image>("thermal/image_raw", 10);
  auto cloud_pub = nh.advertise<sensor_msgs::PointCloud2>("calibration_node/overlay_cloud", 10);
  ASSERT_TRUE(waitFor(kHangGuardS, [&] {
    return image_pub.getNumSubscribers() > 0 && cloud_pub.getNumSubscribers() > 0 &&
           overlay_sub.getNumPublishers() > 0;
  }));

  // The overlay drawn on a new (black) thermal image: each has a stamp of its own, just after
  // the drive's (the data time the node has), and the test waits for the overlay of that stamp.
  ros::Time next_stamp = ros::Time::now();
  const auto drawn = [&]() -> std::vector<std::uint8_t> {
    next_stamp += ros::Duration(0.001);
    const ros::Time stamp = next_stamp;
    image_pub.publish(monoImage(stamp, 640, 512));
    std::vector<std::uint8_t> pixels;
    const bool seen = waitFor(kHangGuardS, [&] {
      std::lock_guard<std::mutex> lock(g_overlays.mutex);
      const auto it = g_overlays.by_stamp.find(stamp);
      if (it == g_overlays.by_stamp.end()) return false;
      pixels = it->second;
      return true;
    });
    if (!seen) ADD_FAILURE() << "no ~overlay for the image stamped " << stamp;
    return pixels;
  };
  // Draws until `wanted` holds for the overlay (the cloud sent before has then been decoded).
  const auto drawUntil = [&](const std::function<bool(const std::vector<std::uint8_t>&)>& wanted) {
    const ros::WallTime give_up = ros::WallTime::now() + ros::WallDuration(kHangGuardS);
    while (ros::ok() && ros::WallTime::now() < give_up) {
      const std::vector<std::uint8_t> pixels = drawn();
      if (pixels.empty()) return false;
      if (wanted(pixels)) return true;
    }
    return false;
  };
  const std::vector<std::uint8_t> without_cloud = drawn();
  ASSERT_FALSE(without_cloud.empty());

  sensor_msgs::PointField f;
  f.datatype = sensor_msgs::PointField::FLOAT32;
  f.count = 1;
  std::vector<sensor_msgs::PointCloud2> bad;
  {
    sensor_msgs::PointCloud2 c = cloudHeader(ros::Time::now());
    for (const char* name : {"x", "y", "z"}) {
      f.name = name;
      c.fields.push_back(f);
      f.offset += 4;
    }
    c.point_step = 16;
    c.data.assign(16, 0);
    c.width = c.height = 0xFFFFFFFFu;
    c.row_step = 0xFFFFFFF0u;
    bad.push_back(c);
    c.width = 100000000u;
    c.height = 1;
    c.row_step = c.width * c.point_step;
    bad.push_back(c);
    c.width = 1;
    c.row_step = 16;
    c.fields[1].name = "x";  // x, x, z
    bad.push_back(c);
  }
  const sensor_msgs::PointCloud2 in_view = cloudInView(T_lidar_camera);
  for (const auto& cloud : bad) {
    const std::string what = std::to_string(cloud.width) + " x " + std::to_string(cloud.height) +
                             " cloud with " + std::to_string(cloud.data.size()) + " bytes";
    cloud_pub.publish(in_view);
    ASSERT_TRUE(drawUntil([&](const std::vector<std::uint8_t>& p) { return p != without_cloud; }))
        << "the cloud in view was never drawn on ~overlay";
    cloud_pub.publish(cloud);
    EXPECT_TRUE(drawUntil([&](const std::vector<std::uint8_t>& p) { return p == without_cloud; }))
        << "~overlay never dropped the cloud in view after a " << what;
    expectAlive("a " + what + " on ~overlay_cloud");
  }
  EXPECT_TRUE(waitFor(kHangGuardS, said({"overlay_cloud", "row_step"}))) << warnings();
}

// A disk that fills during a dataset append: rosbag::BagIOException ended the node (abort). Now
// recording stops, ~status, /diagnostics and /rosout say so with the path and the free space,
// the node keeps collecting in memory and finishes, and the bag holds exactly the pairs
// ~status says it holds.
TEST(NodeDiskFull, RecordingStopsAndCollectingGoesOn) {
  const std::string bag = ros::NodeHandle("~").param<std::string>("dataset_bag", "");
  ASSERT_FALSE(bag.empty());
  ASSERT_TRUE(waitFor(kHangGuardS, [] { return !g_observed.last_status.recording_error.empty(); }))
      << "recording never stopped: " << g_observed.last_status;
  {
    std::lock_guard<std::mutex> lock(g_observed.mutex);
    EXPECT_FALSE(g_observed.last_status.recording);
    EXPECT_NE(g_observed.last_status.recording_error.find(bag), std::string::npos)
        << g_observed.last_status.recording_error;
    EXPECT_NE(g_observed.last_status.recording_error.find("free"), std::string::npos)
        << g_observed.last_status.recording_error;
  }
  EXPECT_TRUE(waitFor(kHangGuardS, said({"recording stopped", bag, "free"}))) << warnings();
  EXPECT_TRUE(waitFor(kHangGuardS, [&] {
    for (const auto& entry : g_observed.diagnostics) {
      const diagnostic_msgs::DiagnosticStatus& s = entry.second;
      if (s.name.find("dataset recording") != std::string::npos &&
          s.level == diagnostic_msgs::DiagnosticStatus::ERROR) {
        for (const auto& kv : s.values) {
          if (kv.value.find(bag) != std::string::npos) return true;
        }
      }
    }
    return false;
  })) << "no ERROR on /diagnostics for the dataset recording";

  ASSERT_TRUE(waitFor(kHangGuardS, [] { return g_observed.last_status.state_name == "done"; }))
      << "the node did not finish: " << g_observed.last_status;
  CalibrationStatus status;
  {
    std::lock_guard<std::mutex> lock(g_observed.mutex);
    status = g_observed.last_status;
  }
  EXPECT_GE(status.pairs_kept, status.pairs_required);
  EXPECT_LT(status.pairs_in_bag, status.pairs_kept);
  EXPECT_GE(status.pairs_in_bag, 1u);
  // The bag on disk is readable and holds what ~status says.
  rosbag::Bag reader(bag, rosbag::bagmode::Read);
  rosbag::View markers(reader, rosbag::TopicQuery("/thermal_lidar_calibration/dataset_pair"));
  EXPECT_EQ(markers.size(), status.pairs_in_bag);
}

std_srvs::Trigger::Response callTrigger(const std::string& service) {
  std_srvs::Trigger trigger;
  EXPECT_TRUE(ros::service::call(service, trigger)) << service << " did not answer";
  return trigger.response;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// ~save and ~reset answered "success" and "the bag holds every kept pair" when nothing was
// written (issue 12, item 4). Now success means the result file was written and read back, and
// the pairs in the bag are counted from the file. Runs after RecordingStopsAndCollectingGoesOn:
// the node is done and its bag holds fewer pairs than it kept.
TEST(NodeDiskFull, SaveAndResetAnswerOnlyWhatTheyChecked) {
  const std::string bag = ros::NodeHandle("~").param<std::string>("dataset_bag", "");
  const std::string output = ros::NodeHandle("~").param<std::string>("output_file", "");
  ASSERT_FALSE(output.empty());
  ASSERT_TRUE(waitFor(kHangGuardS, [] { return g_observed.last_status.state_name == "done"; }));
  // Frames after ~reset would start a new bag: wait until the node has taken the whole drive.
  ASSERT_TRUE(waitFor(kHangGuardS, [] { return g_observed.player_done_messages.has_value(); }))
      << "the player did not finish: " << g_observed.last_status;
  CalibrationStatus status;
  {
    std::lock_guard<std::mutex> lock(g_observed.mutex);
    status = g_observed.last_status;
  }
  std::size_t on_disk = 0, candidates = 0;
  {
    rosbag::Bag reader(bag, rosbag::bagmode::Read);
    on_disk = rosbag::View(reader, rosbag::TopicQuery("/thermal_lidar_calibration/dataset_pair")).size();
    candidates = rosbag::View(reader, rosbag::TopicQuery("/thermal_lidar_calibration/dataset_candidate")).size();
  }
  const std::string holds = "holds " + std::to_string(on_disk) + " of the " +
                            std::to_string(status.pairs_kept) + " kept pairs" +
                            (candidates > 0 ? " and " + std::to_string(candidates) + " association candidates" : "");
  std::cerr << "the bag holds " << on_disk << " pairs and " << candidates << " association candidates\n";

  std_srvs::Trigger::Response r = callTrigger("calibration_node/save");
  EXPECT_TRUE(r.success) << r.message;
  EXPECT_TRUE(contains(r.message, "read back")) << r.message;
  EXPECT_TRUE(contains(r.message, holds)) << r.message << " (expected '" << holds << "')";
  EXPECT_TRUE(contains(r.message, "recording stopped")) << r.message;

  // The result cannot be written (its temporary file's place is taken by a directory).
  ASSERT_EQ(::mkdir((output + ".tmp").c_str(), 0755), 0);
  r = callTrigger("calibration_node/save");
  EXPECT_FALSE(r.success) << r.message;
  EXPECT_TRUE(contains(r.message, "NOT written")) << r.message;
  EXPECT_TRUE(contains(r.message, holds)) << r.message;
  ::rmdir((output + ".tmp").c_str());

  r = callTrigger("calibration_node/reset");
  EXPECT_TRUE(contains(r.message, "deleted " + bag)) << r.message;
  r = callTrigger("calibration_node/reset");
  EXPECT_FALSE(contains(r.message, "deleted")) << r.message;
  EXPECT_TRUE(contains(r.message, "did not exist")) << r.message;
  r = callTrigger("calibration_node/save");
  EXPECT_FALSE(r.success) << r.message;
  EXPECT_TRUE(contains(r.message, "no result to write yet")) << r.message;
  EXPECT_TRUE(contains(r.message, "no dataset bag on disk")) << r.message;
  EXPECT_FALSE(contains(r.message, "holds")) << r.message;
}

int main(int argc, char** argv) { return runNodeTests(argc, argv, "node_hostile_test"); }
