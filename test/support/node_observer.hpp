#pragma once
// What a rostest observes of a running calibration_node: its ~status, its /rosout lines of WARN
// and above, /diagnostics, the images it was sent, and the paced_bag_player of the .test (its
// ~paused and ~done); waiting for a condition on them; and the check that the node is still up.
// Shared by the node rostests. A test's main() calls subscribeToNode() and runs an AsyncSpinner.
//
// Time enters these tests through the node, never through the machine: a test waits for the
// state it needs (a ~status count, a line, the player's ~done), with kHangGuardS as the deadline
// of every wait. That deadline only stops a hung test; a slow machine reaches the state later.

#include <thermal_lidar_calibration/CalibrationStatus.h>

#include <diagnostic_msgs/DiagnosticArray.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <rosgraph_msgs/Log.h>
#include <sensor_msgs/Image.h>
#include <std_msgs/UInt32.h>
#include <std_msgs/UInt32MultiArray.h>
#include <std_srvs/Trigger.h>
#include <tf2_msgs/TFMessage.h>

#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace node_observer {

using thermal_lidar_calibration::CalibrationStatus;

// The deadline of every wait on the node's state: generous, a guard against hangs only.
constexpr double kHangGuardS = 120.0;

struct Observed {
  std::mutex mutex;
  std::vector<std::string> states;  // distinct consecutive state names
  CalibrationStatus last_status;
  int status_messages = 0;
  // child frame -> (publisher, transform) for every /tf_static transform seen
  std::multimap<std::string, std::pair<std::string, geometry_msgs::TransformStamped>> tf_static;
  std::vector<std::string> node_tf_static_children;  // of the node's latest /tf_static message
  int overlay_images = 0;
  std::vector<std::string> node_warnings;  // /rosout WARN+ from calibration_node
  std::vector<ros::Time> node_warning_stamps;  // their header stamps (when the node said them)
  std::vector<ros::WallTime> node_warning_received;  // when this test received them
  std::map<std::string, diagnostic_msgs::DiagnosticStatus> diagnostics;  // latest, by name
  // The first ~status that said, while collecting before any fit, what the data covers and what
  // is missing (~stop_when quality).
  std::optional<CalibrationStatus> first_collecting_coverage;
  // The .test's paced_bag_player (named "player"): the pairs the node had kept when it paused,
  // and the messages it played once the node had taken them all.
  std::optional<std::uint32_t> player_paused_pairs, player_done_messages;
};
inline Observed g_observed;

inline void onStatus(const CalibrationStatus::ConstPtr& msg) {
  std::lock_guard<std::mutex> lock(g_observed.mutex);
  if (g_observed.states.empty() || g_observed.states.back() != msg->state_name) {
    g_observed.states.push_back(msg->state_name);
  }
  g_observed.last_status = *msg;
  ++g_observed.status_messages;
  if (!g_observed.first_collecting_coverage && msg->state == CalibrationStatus::COLLECTING &&
      !msg->quality_missing.empty() && msg->final_loss == 0.0) {
    g_observed.first_collecting_coverage = *msg;
  }
}

inline void onTfStatic(const ros::MessageEvent<tf2_msgs::TFMessage const>& event) {
  std::lock_guard<std::mutex> lock(g_observed.mutex);
  for (const auto& t : event.getMessage()->transforms) {
    g_observed.tf_static.emplace(t.child_frame_id, std::make_pair(event.getPublisherName(), t));
  }
  if (event.getPublisherName().find("calibration_node") != std::string::npos) {
    g_observed.node_tf_static_children.clear();
    for (const auto& t : event.getMessage()->transforms) g_observed.node_tf_static_children.push_back(t.child_frame_id);
  }
}

inline void onOverlay(const sensor_msgs::Image::ConstPtr&) {
  std::lock_guard<std::mutex> lock(g_observed.mutex);
  ++g_observed.overlay_images;
}

inline void onDiagnostics(const diagnostic_msgs::DiagnosticArray::ConstPtr& msg) {
  std::lock_guard<std::mutex> lock(g_observed.mutex);
  for (const auto& status : msg->status) g_observed.diagnostics[status.name] = status;
}

inline void onRosout(const rosgraph_msgs::Log::ConstPtr& msg) {
  if (msg->level < rosgraph_msgs::Log::WARN) return;
  if (msg->name.find("calibration_node") == std::string::npos) return;
  std::lock_guard<std::mutex> lock(g_observed.mutex);
  g_observed.node_warnings.push_back(msg->msg);
  g_observed.node_warning_stamps.push_back(msg->header.stamp);
  g_observed.node_warning_received.push_back(ros::WallTime::now());
}

inline void onPlayerPaused(const std_msgs::UInt32::ConstPtr& msg) {
  std::lock_guard<std::mutex> lock(g_observed.mutex);
  g_observed.player_paused_pairs = msg->data;
}

inline void onPlayerDone(const std_msgs::UInt32::ConstPtr& msg) {
  std::lock_guard<std::mutex> lock(g_observed.mutex);
  g_observed.player_done_messages = msg->data;
}

// The subscriptions the helpers read; keep the returned subscribers alive.
inline std::vector<ros::Subscriber> subscribeToNode(ros::NodeHandle& nh) {
  return {nh.subscribe("calibration_node/status", 100, onStatus),
          nh.subscribe("/tf_static", 100, onTfStatic),
          nh.subscribe("/rosout", 1000, onRosout),
          nh.subscribe("/diagnostics", 100, onDiagnostics),
          nh.subscribe("/player/paused", 1, onPlayerPaused),
          nh.subscribe("/player/done", 1, onPlayerDone)};
}

// Waits until `predicate` holds (evaluated under g_observed.mutex); false after `timeout_s`.
inline bool waitFor(double timeout_s, const std::function<bool()>& predicate) {
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout_s);
  while (ros::ok() && ros::WallTime::now() < end) {
    {
      std::lock_guard<std::mutex> lock(g_observed.mutex);
      if (predicate()) return true;
    }
    ros::WallDuration(0.05).sleep();
  }
  std::lock_guard<std::mutex> lock(g_observed.mutex);
  return predicate();
}

// Messages the node has counted on its input topics (~status images/masks/clusters_received).
struct InputCounts {
  std::uint32_t images = 0, masks = 0, clusters = 0;
};

inline InputCounts inputsTaken() {
  std::lock_guard<std::mutex> lock(g_observed.mutex);
  const CalibrationStatus& s = g_observed.last_status;
  return {s.images_received, s.masks_received, s.clusters_received};
}

// Waits until the node has counted at least `expected` on each input: what a test publishes
// next then cannot overflow the node's subscriber queues, and what it published has arrived.
inline bool waitForInputsTaken(const InputCounts& expected) {
  return waitFor(kHangGuardS, [&] {
    const CalibrationStatus& s = g_observed.last_status;
    return s.images_received >= expected.images && s.masks_received >= expected.masks &&
           s.clusters_received >= expected.clusters;
  });
}

// Resumes the paused player; `sent` is what this test published to the node's inputs during the
// pause (the player counts on the node's ~status totals). Latched: the player gets it whenever
// it connects.
inline void resumePlayer(const InputCounts& sent = {}) {
  static ros::Publisher resume =
      ros::NodeHandle().advertise<std_msgs::UInt32MultiArray>("/player/resume", 1, /*latch=*/true);
  std_msgs::UInt32MultiArray msg;
  msg.data = {sent.images, sent.masks, sent.clusters};
  resume.publish(msg);
}

// True when the node said something containing every one of `parts` on /rosout.
inline std::function<bool()> said(std::vector<std::string> parts) {
  return [parts] {
    for (const auto& w : g_observed.node_warnings) {
      bool all = true;
      for (const auto& p : parts) all = all && w.find(p) != std::string::npos;
      if (all) return true;
    }
    return false;
  };
}

inline std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : " -> ") + x;
  return s;
}

inline std::string warnings() {
  std::string s;
  for (const auto& w : g_observed.node_warnings) s += "\n  " + w;
  return s;
}

// The node is up: ~status keeps coming and ~save answers (success or not).
inline void expectAlive(const std::string& after) {
  int before = 0;
  {
    std::lock_guard<std::mutex> lock(g_observed.mutex);
    before = g_observed.status_messages;
  }
  EXPECT_TRUE(waitFor(kHangGuardS, [&] { return g_observed.status_messages > before + 2; }))
      << "~status stopped after " << after;
  std_srvs::Trigger trigger;
  ros::ServiceClient save =
      ros::NodeHandle().serviceClient<std_srvs::Trigger>("calibration_node/save");
  EXPECT_TRUE(save.waitForExistence(ros::Duration(kHangGuardS))) << "~save gone after " << after;
  EXPECT_TRUE(save.call(trigger)) << "~save did not answer after " << after;
}

// A rostest program's main(): gtest and ROS initialised, the node observed, the tests run with
// callbacks served on two threads.
inline int runNodeTests(int argc, char** argv, const char* node_name) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, node_name);
  ros::NodeHandle nh;
  const std::vector<ros::Subscriber> subscribers = subscribeToNode(nh);
  ros::AsyncSpinner spinner(2);
  spinner.start();
  const int result = RUN_ALL_TESTS();
  spinner.stop();
  ros::shutdown();
  return result;
}

}  // namespace node_observer
