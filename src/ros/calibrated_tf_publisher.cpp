// Static transform of the result, checked against the live tf tree first.

#include "thermal_lidar_calibration/ros/calibrated_tf_publisher.hpp"

#include <Eigen/Geometry>


namespace thermal_lidar_calibration {
namespace ros_io {

geometry_msgs::TransformStamped toTransformMsg(const Extrinsic& extrinsic,
                                               const std::string& lidar_frame,
                                               const std::string& child_frame, ros::Time stamp) {
  const Eigen::Isometry3d T_lidar_camera = extrinsic.T_camera_lidar().inverse();
  const Eigen::Quaterniond q(T_lidar_camera.rotation());
  geometry_msgs::TransformStamped msg;
  msg.header.stamp = stamp;
  msg.header.frame_id = lidar_frame;
  msg.child_frame_id = child_frame;
  msg.transform.translation.x = T_lidar_camera.translation().x();
  msg.transform.translation.y = T_lidar_camera.translation().y();
  msg.transform.translation.z = T_lidar_camera.translation().z();
  msg.transform.rotation.x = q.x();
  msg.transform.rotation.y = q.y();
  msg.transform.rotation.z = q.z();
  msg.transform.rotation.w = q.w();
  return msg;
}

CalibratedTfPublisher::CalibratedTfPublisher(std::string child_frame_param)
    : child_frame_param_(std::move(child_frame_param)), listener_(buffer_) {}

CalibratedTfPublisher::Decision CalibratedTfPublisher::chooseChildFrame(
    const std::string& lidar_frame, const std::string& camera_frame) const {
  const std::string fallback =
      child_frame_param_.empty() ? camera_frame + "_calibrated" : child_frame_param_;
  // Our own earlier result may be replaced (it is the same edge).
  if (published_child_ == camera_frame && published_parent_ == lidar_frame) return {camera_frame, ""};
  if (buffer_._frameExists(camera_frame)) {
    std::string parent;
    if (buffer_._getParent(camera_frame, ros::Time(0), parent)) {
      return {fallback, "'" + camera_frame + "' already has the parent '" + parent + "'"};
    }
    if (buffer_._frameExists(lidar_frame) &&
        buffer_.canTransform(lidar_frame, camera_frame, ros::Time(0))) {
      return {fallback, "'" + camera_frame + "' is already connected to '" + lidar_frame +
                            "' in the tf tree"};
    }
  }
  return {camera_frame, ""};
}

geometry_msgs::TransformStamped CalibratedTfPublisher::publish(const Extrinsic& extrinsic,
                                                               const std::string& lidar_frame,
                                                               const std::string& camera_frame,
                                                               Decision* decision) {
  Decision chosen = chooseChildFrame(lidar_frame, camera_frame);
  if (chosen.child_frame != camera_frame && chosen.child_frame != published_child_) {
    // The fallback frame must not have a parent either (unless it is ours).
    std::string parent;
    if (buffer_._frameExists(chosen.child_frame) &&
        buffer_._getParent(chosen.child_frame, ros::Time(0), parent)) {
      chosen.reason += "; '" + chosen.child_frame + "' also has a parent ('" + parent +
                       "'), so '" + chosen.child_frame + "_2' is used";
      chosen.child_frame += "_2";
    }
  }
  const geometry_msgs::TransformStamped msg =
      toTransformMsg(extrinsic, lidar_frame, chosen.child_frame, ros::Time::now());
  broadcaster_.sendTransform(msg);
  published_parent_ = lidar_frame;
  published_child_ = chosen.child_frame;
  if (decision) *decision = chosen;
  return msg;
}

}  // namespace ros_io
}  // namespace thermal_lidar_calibration

