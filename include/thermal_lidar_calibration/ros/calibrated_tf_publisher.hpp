#pragma once
// Publishes the result on /tf_static (parent = LiDAR frame, child = camera frame) without ever
// giving a frame a second parent: it listens to /tf and /tf_static from construction on, and if
// the camera frame already has a parent (or is already connected to the LiDAR frame) the result
// goes out under `fallback_child` (default "<camera_frame>_calibrated").
//
// Besides a tf2 buffer (which forgets everything when sim time jumps back, as a replayed bag
// makes it do) it keeps its own record of every parent other nodes have given a frame, from
// raw subscriptions that know each message's publisher. And it keeps watching after publishing:
// a parent for the camera frame that arrives later (a robot's /tf_static sent once, unlatched,
// or a bag's replayed after the node published) is a conflict, and moveToFallback() replaces the
// node's latched /tf_static message with the fallback child (listeners that already hold the
// old edge keep it until they restart: the node says so).

#include "thermal_lidar_calibration/core/extrinsic.hpp"

#include <geometry_msgs/TransformStamped.h>
#include <ros/ros.h>
#include <tf2_msgs/TFMessage.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include <map>
#include <mutex>
#include <optional>
#include <string>

namespace thermal_lidar_calibration {
namespace ros_io {

// T_lidar_camera as a TransformStamped (header.frame_id = lidar, child_frame_id = child): tf's
// transform is the pose of the child in the parent, i.e. the inverse of p_C = R p_L + t.
geometry_msgs::TransformStamped toTransformMsg(const Extrinsic& extrinsic,
                                               const std::string& lidar_frame,
                                               const std::string& child_frame, ros::Time stamp);

class CalibratedTfPublisher {
 public:
  // `child_frame_param`: ~child_frame ("" = "<camera_frame>_calibrated").
  explicit CalibratedTfPublisher(std::string child_frame_param);

  struct Decision {
    std::string child_frame;
    std::string reason;  // empty when the camera frame itself is used
  };
  // Which child frame the result may use, given what the tf tree holds now.
  Decision chooseChildFrame(const std::string& lidar_frame, const std::string& camera_frame) const;
  // Chooses the child frame and publishes; returns the message sent.
  geometry_msgs::TransformStamped publish(const Extrinsic& extrinsic, const std::string& lidar_frame,
                                          const std::string& camera_frame, Decision* decision);

  // The extrinsic the tf tree holds now between the two frames (p_C = R p_L + t), for the drift
  // watch's reference; nullopt with the reason in `error` when they are not connected.
  std::optional<Extrinsic> lookupExtrinsic(const std::string& lidar_frame,
                                           const std::string& camera_frame,
                                           std::string* error) const;

  // After publishing under the camera frame itself: another node has since given it a parent.
  // The conflict in words (both parents, who published the other), or nullopt.
  std::optional<std::string> conflictAfterPublishing() const;
  // Publishes the last result again under the fallback child instead (replacing this node's
  // latched /tf_static message); returns the new child frame.
  std::string moveToFallback();

 private:
  void onTf(const ros::MessageEvent<tf2_msgs::TFMessage const>& event);
  std::optional<std::string> otherParent(const std::string& frame) const;  // "parent (by /node)"
  std::string fallbackFor(const std::string& camera_frame) const;

  std::string child_frame_param_;
  tf2_ros::Buffer buffer_;
  tf2_ros::TransformListener listener_;
  ros::Publisher tf_static_pub_;  // latched: our one transform, replaceable
  ros::Subscriber tf_sub_, tf_static_sub_;
  mutable std::mutex mutex_;  // others_ (filled on the subscription's callback queue)
  std::map<std::string, std::string> others_;  // child frame -> "parent (by /publisher)"
  std::string published_parent_, published_child_, published_camera_;  // what this node sent last
  std::optional<Extrinsic> published_extrinsic_;
};

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
