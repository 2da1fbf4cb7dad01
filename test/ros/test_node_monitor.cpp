// rostests of calibration_node's drift watch (~mode: monitor, issue 9), run by node_monitor.test
// (a bag with a bump mid-drive, ~auto_update on) and node_monitor_stable.test (a stable drive).
//
// NodeMonitor.ConfirmsTheBumpAndPublishesTheNewExtrinsic: ~status says OK before the change and
//   ERROR after it; with ~auto_update the node's /tf_static transform ends near the new truth,
//   and the result file holds it with its history.
// NodeMonitor.AStableDriveStaysOk: no WARN or ERROR at any time, nothing published; the extrinsic
//   watched is the one the tf tree holds.

#include "thermal_lidar_calibration/app/files/result_file.hpp"
#include "thermal_lidar_calibration/core/extrinsic.hpp"

#include "../support/node_observer.hpp"

#include <Eigen/Geometry>
#include <tf2_ros/static_transform_broadcaster.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <string>
#include <vector>

using namespace node_observer;
using thermal_lidar_calibration::Extrinsic;

namespace {

// (data time, drift state) of every ~status message, in order.
struct Timeline {
  std::mutex mutex;
  std::vector<std::pair<double, std::string>> states;
  // A ~status that named the new extrinsic's model with its 95 % half-widths.
  bool saw_update_intervals = false;
};
Timeline g_timeline;

void onStatusTimeline(const CalibrationStatus::ConstPtr& msg) {
  std::lock_guard<std::mutex> lock(g_timeline.mutex);
  g_timeline.states.emplace_back(msg->header.stamp.toSec(), msg->drift_state);
  if (!msg->drift_update_model.empty() && msg->drift_update_translation_halfwidth_cm[0] > 0.0) {
    g_timeline.saw_update_intervals = true;
  }
}

// The drive is over and the watch has tested every pair of it: the player has played the whole
// bag (the node took every message, and with --hold-while-drift-busy the watch kept up), and a
// ~status after that says the watch has nothing left to test and no update left to take.
bool waitForDriveTested() {
  if (!waitFor(kHangGuardS * 4, [] { return g_observed.player_done_messages.has_value(); })) return false;
  int after_done = 0;
  {
    std::lock_guard<std::mutex> lock(g_observed.mutex);
    after_done = g_observed.status_messages;
  }
  return waitFor(kHangGuardS, [&] {
    const CalibrationStatus& s = g_observed.last_status;
    return g_observed.status_messages > after_done && s.drift_pairs_waiting == 0 && !s.drift_update_ready;
  });
}

Extrinsic nodePublished(const std::string& child) {
  geometry_msgs::TransformStamped published;
  for (auto r = g_observed.tf_static.equal_range(child); r.first != r.second; ++r.first) {
    if (r.first->second.first.find("calibration_node") != std::string::npos) {
      published = r.first->second.second;
    }
  }
  const auto& q = published.transform.rotation;
  const auto& t = published.transform.translation;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();  // T_lidar_camera: the camera in the LiDAR
  T.linear() = Eigen::Quaterniond(q.w, q.x, q.y, q.z).normalized().toRotationMatrix();
  T.translation() = Eigen::Vector3d(t.x, t.y, t.z);
  const Eigen::Isometry3d T_camera_lidar = T.inverse();
  return Extrinsic::fromRotationMatrix(T_camera_lidar.linear(), T_camera_lidar.translation());
}

Extrinsic extrinsicOf(const YAML::Node& node) {
  Extrinsic e;
  for (int i = 0; i < 3; ++i) {
    e.rotation_vector[i] = node["rotation_vector"][i].as<double>();
    e.translation[i] = node["translation"][i].as<double>();
  }
  return e;
}

}  // namespace

TEST(NodeMonitor, ConfirmsTheBumpAndPublishesTheNewExtrinsic) {
  ros::NodeHandle pnh("~");
  const std::string truth_file = pnh.param<std::string>("truth_file", "");
  const std::string result_file = pnh.param<std::string>("result_file", "");
  const std::string child = pnh.param<std::string>("expected_child", "thermal_optical");
  const double rot_tol_deg = pnh.param("rotation_tolerance_deg", 0.15);
  const double trans_tol_m = pnh.param("translation_tolerance_m", 0.02);
  ros::NodeHandle nh;
  const ros::Subscriber sub = nh.subscribe("calibration_node/status", 1000, onStatusTimeline);
  ASSERT_TRUE(waitForDriveTested()) << "the drive was not played and tested: " << g_observed.last_status;

  const YAML::Node truth = YAML::LoadFile(truth_file);
  const double change_at = truth["extrinsic_change"]["at_stamp"].as<double>();
  const Extrinsic after = extrinsicOf(truth["extrinsic_change"]["after"]);
  double first_error = 0.0;
  int ok_before = 0;
  {
    std::lock_guard<std::mutex> lock(g_timeline.mutex);
    for (const auto& [stamp, state] : g_timeline.states) {
      if (stamp < change_at) {
        EXPECT_TRUE(state == "OK" || state.empty()) << state << " at " << stamp << ", before the change";
        ok_before += state == "OK" ? 1 : 0;
      } else if (state == "ERROR" && first_error == 0.0) {
        first_error = stamp;
      }
    }
  }
  EXPECT_GT(ok_before, 0) << "the watch never reported before the change";
  ASSERT_GT(first_error, 0.0) << "no ERROR after the change";
  std::cout << "[ node ] drift confirmed " << first_error - change_at << " s after the change\n";

  std::lock_guard<std::mutex> lock(g_observed.mutex);
  EXPECT_EQ(g_observed.last_status.state_name, "monitoring");
  EXPECT_GE(g_observed.last_status.drift_updates, 1u);
  // Issue 23: the watch pairs by association too (the default pairing), counted among its pairs.
  EXPECT_GT(g_observed.last_status.drift_association_pairs, 0u) << g_observed.last_status;
  EXPECT_LT(g_observed.last_status.drift_association_pairs, g_observed.last_status.drift_pairs_seen);
  const Extrinsic published = nodePublished(child);
  const double rot_err_deg = thermal_lidar_calibration::rotationErrorRad(published, after) * 180.0 / M_PI;
  const double trans_err_m = thermal_lidar_calibration::translationErrorM(published, after);
  std::cout << "[ node ] new extrinsic on /tf_static: " << rot_err_deg << " deg, " << trans_err_m * 100
            << " cm from the new truth\n";
  EXPECT_LT(rot_err_deg, rot_tol_deg);
  EXPECT_LT(trans_err_m, trans_tol_m);
  // The result file holds what was published, with the history of updates.
  const YAML::Node result = YAML::LoadFile(result_file);
  ASSERT_TRUE(result["drift_updates"]) << result_file;
  EXPECT_EQ(result["drift_updates"].size(), g_observed.last_status.drift_updates);
  EXPECT_EQ(result["drift_updates"][0]["accepted_by"].as<std::string>(), "auto_update");
  // Each update says what motion was fitted and how far its pairs pin it down.
  const YAML::Node last_update = result["drift_updates"][result["drift_updates"].size() - 1];
  EXPECT_TRUE(last_update["model"]) << result_file;
  ASSERT_TRUE(last_update["uncertainty"]) << result_file;
  EXPECT_EQ(last_update["uncertainty"]["translation_cm"].size(), 3u);
  EXPECT_GT(last_update["uncertainty"]["translation_cm"][0].as<double>(), 0.0);
  {
    std::lock_guard<std::mutex> timeline_lock(g_timeline.mutex);
    EXPECT_TRUE(g_timeline.saw_update_intervals) << "no ~status named the new fit's model and intervals";
  }
  const Extrinsic from_file = thermal_lidar_calibration::readExtrinsicFile(result_file);
  EXPECT_LT(thermal_lidar_calibration::rotationErrorRad(from_file, published), 1e-6);
  EXPECT_LT(thermal_lidar_calibration::translationErrorM(from_file, published), 1e-6);
  const Extrinsic old_in_file = extrinsicOf(result["drift_updates"][0]["old"]);
  EXPECT_LT(thermal_lidar_calibration::rotationErrorRad(old_in_file, thermal_lidar_calibration::readExtrinsicFile(truth_file)), 1e-6);
}

TEST(NodeMonitor, AStableDriveStaysOk) {
  ros::NodeHandle pnh("~");
  ros::NodeHandle nh;
  // The robot's tf: the extrinsic in use, velodyne -> thermal_optical.
  std::vector<double> v;
  ASSERT_TRUE(pnh.getParam("robot_tf", v) && v.size() == 7) << "~robot_tf: x y z qx qy qz qw";
  tf2_ros::StaticTransformBroadcaster robot_tf;
  geometry_msgs::TransformStamped t;
  t.header.frame_id = "velodyne";
  t.child_frame_id = "thermal_optical";
  t.transform.translation.x = v[0];
  t.transform.translation.y = v[1];
  t.transform.translation.z = v[2];
  t.transform.rotation.x = v[3];
  t.transform.rotation.y = v[4];
  t.transform.rotation.z = v[5];
  t.transform.rotation.w = v[6];
  robot_tf.sendTransform(t);
  const ros::Subscriber sub = nh.subscribe("calibration_node/status", 1000, onStatusTimeline);
  // The player starts paused (node_monitor_stable.test): the drive begins once the robot's tf is
  // out, so that the node finds it at the first frame.
  resumePlayer();
  ASSERT_TRUE(waitForDriveTested()) << "the drive was not played and tested: " << g_observed.last_status;
  {
    std::lock_guard<std::mutex> lock(g_timeline.mutex);
    for (const auto& [stamp, state] : g_timeline.states) {
      EXPECT_TRUE(state == "OK" || state.empty()) << state << " at " << stamp << " on a stable drive";
    }
  }
  std::lock_guard<std::mutex> lock(g_observed.mutex);
  EXPECT_GE(g_observed.last_status.drift_tests, pnh.param("min_tests", 10)) << g_observed.last_status;
  EXPECT_EQ(g_observed.last_status.drift_updates, 0u);
  EXPECT_EQ(g_observed.last_status.drift_reference, pnh.param<std::string>("expected_reference", ""));
  EXPECT_TRUE(g_observed.node_tf_static_children.empty()) << "published on a stable drive";
  const auto diagnostics = g_observed.diagnostics.find("calibration_node: drift");
  ASSERT_NE(diagnostics, g_observed.diagnostics.end()) << "no drift status on /diagnostics";
  EXPECT_EQ(diagnostics->second.level, diagnostic_msgs::DiagnosticStatus::OK) << diagnostics->second.message;
}

int main(int argc, char** argv) { return runNodeTests(argc, argv, "node_monitor_test"); }
