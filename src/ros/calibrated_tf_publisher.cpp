// Static transform of the result, checked against the live tf tree first.

#include "thermal_lidar_calibration/ros/calibrated_tf_publisher.hpp"

#include "thermal_lidar_calibration/ros/msg_conversion.hpp"

#include <Eigen/Geometry>
#include <ros/this_node.h>



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
    : child_frame_param_(std::move(child_frame_param)), listener_(buffer_) {
  ros::NodeHandle nh;
  tf_static_pub_ = nh.advertise<tf2_msgs::TFMessage>("/tf_static", 10, /*latch=*/true);
  tf_static_sub_ = nh.subscribe("/tf_static", 100, &CalibratedTfPublisher::onTf, this);
  tf_sub_ = nh.subscribe("/tf", 100, &CalibratedTfPublisher::onTf, this);
}

void CalibratedTfPublisher::onTf(const ros::MessageEvent<tf2_msgs::TFMessage const>& event) {
  if (event.getPublisherName() == ros::this_node::getName()) return;  // our own result
  std::lock_guard<std::mutex> lock(mutex_);
  for (const auto& t : event.getMessage()->transforms) {
    others_[tfFrameId(t.child_frame_id)] = "'" + tfFrameId(t.header.frame_id) + "' (from " + event.getPublisherName() + ")";
  }
}

std::optional<std::string> CalibratedTfPublisher::otherParent(const std::string& frame) const {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto it = others_.find(frame);
  if (it == others_.end()) return std::nullopt;
  return it->second;
}

std::string CalibratedTfPublisher::fallbackFor(const std::string& camera_frame) const {
  return child_frame_param_.empty() ? camera_frame + "_calibrated" : child_frame_param_;
}

std::optional<std::string> CalibratedTfPublisher::conflictAfterPublishing() const {
  if (published_child_.empty() || published_child_ != published_camera_) return std::nullopt;
  const auto parent = otherParent(published_child_);
  if (!parent) return std::nullopt;
  return "'" + published_child_ + "' now also has the parent " + *parent + " besides this node's '" +
         published_parent_ + "'";
}

std::string CalibratedTfPublisher::moveToFallback() {
  if (!published_extrinsic_) return published_child_;
  std::string child = fallbackFor(published_camera_);
  if (otherParent(child)) child += "_2";
  tf2_msgs::TFMessage msg;
  msg.transforms.push_back(toTransformMsg(*published_extrinsic_, published_parent_, child, ros::Time::now()));
  tf_static_pub_.publish(msg);
  published_child_ = child;
  return child;
}

CalibratedTfPublisher::Decision CalibratedTfPublisher::chooseChildFrame(
    const std::string& lidar_frame, const std::string& camera_frame) const {
  const std::string fallback = fallbackFor(camera_frame);
  // Our own earlier result may be replaced (it is the same edge).
  if (published_child_ == camera_frame && published_parent_ == lidar_frame) return {camera_frame, ""};
  if (const auto parent = otherParent(camera_frame)) {
    return {fallback, "'" + camera_frame + "' already has the parent " + *parent};
  }
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

std::optional<Extrinsic> CalibratedTfPublisher::lookupExtrinsic(const std::string& lidar_frame,
                                                                 const std::string& camera_frame,
                                                                 std::string* error) const {
  try {
    // Maps points of the source (LiDAR) frame into the target (camera) frame: p_C = R p_L + t.
    const geometry_msgs::TransformStamped tf =
        buffer_.lookupTransform(camera_frame, lidar_frame, ros::Time(0));
    const auto& q = tf.transform.rotation;
    const auto& t = tf.transform.translation;
    const Eigen::Quaterniond rotation(q.w, q.x, q.y, q.z);
    return Extrinsic::fromRotationMatrix(rotation.normalized().toRotationMatrix(),
                                         Eigen::Vector3d(t.x, t.y, t.z));
  } catch (const tf2::TransformException& e) {
    if (error) *error = e.what();
    return std::nullopt;
  }
}

geometry_msgs::TransformStamped CalibratedTfPublisher::publish(const Extrinsic& extrinsic,
                                                               const std::string& lidar_frame,
                                                               const std::string& camera_frame,
                                                               Decision* decision) {
  Decision chosen = chooseChildFrame(lidar_frame, camera_frame);
  if (chosen.child_frame != camera_frame && chosen.child_frame != published_child_) {
    // The fallback frame must not have a parent either (unless it is ours).
    std::string parent;
    if (const auto other = otherParent(chosen.child_frame)) {
      parent = *other;
    } else if (buffer_._frameExists(chosen.child_frame)) {
      buffer_._getParent(chosen.child_frame, ros::Time(0), parent);
    }
    if (!parent.empty()) {
      chosen.reason += "; '" + chosen.child_frame + "' also has a parent (" + parent +
                       "), so '" + chosen.child_frame + "_2' is used";
      chosen.child_frame += "_2";
    }
  }
  const geometry_msgs::TransformStamped msg =
      toTransformMsg(extrinsic, lidar_frame, chosen.child_frame, ros::Time::now());
  tf2_msgs::TFMessage latched;  // replaces this node's earlier message for late subscribers
  latched.transforms.push_back(msg);
  tf_static_pub_.publish(latched);
  published_parent_ = lidar_frame;
  published_child_ = chosen.child_frame;
  published_camera_ = camera_frame;
  published_extrinsic_ = extrinsic;
  if (decision) *decision = chosen;
  return msg;
}

}  // namespace ros_io
}  // namespace thermal_lidar_calibration

