#pragma once
// Publishes the result on /tf_static (parent = LiDAR frame, child = camera frame) without ever
// giving a frame a second parent: it listens to /tf and /tf_static from construction on, and if
// the camera frame already has a parent (or is already connected to the LiDAR frame) the result
// goes out under `fallback_child` (default "<camera_frame>_calibrated").

#include "thermal_lidar_calibration/core/extrinsic.hpp"

#include <geometry_msgs/TransformStamped.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <tf2_ros/transform_listener.h>

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

 private:
  std::string child_frame_param_;
  tf2_ros::Buffer buffer_;
  tf2_ros::TransformListener listener_;
  tf2_ros::StaticTransformBroadcaster broadcaster_;
  std::string published_parent_, published_child_;  // what this node sent last
};

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
