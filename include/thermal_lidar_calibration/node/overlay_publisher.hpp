#pragma once
// ~overlay (sensor_msgs/Image, bgr8): every new thermal image with the latest person clusters
// projected by the current estimate and, when ~overlay_cloud carries the full point cloud, all
// its points coloured by range. Renders only while someone subscribes; inputs are cached by
// pointer in the callbacks, decoding happens at most once per message.

#include "thermal_lidar_calibration/core/camera_model.hpp"
#include "thermal_lidar_calibration/core/extrinsic.hpp"
#include "thermal_lidar_calibration/core/person_motion.hpp"
#include "thermal_lidar_calibration/ros/msg_conversion.hpp"
#include "thermal_lidar_calibration/node/overlay_renderer.hpp"

#include <image_transport/image_transport.h>
#include <ros/node_handle.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace thermal_lidar_calibration {
namespace ros_io {

class OverlayPublisher {
 public:
  // Advertises ~overlay on `private_nh`; ~overlay_cloud is subscribed only while someone
  // watches ~overlay (a full cloud at 10 Hz costs its deserialization even when nobody looks).
  OverlayPublisher(ros::NodeHandle& private_nh, int max_points, std::string clusters_topic);

  void setCamera(const CameraModel& camera);
  void setEstimate(const std::optional<Extrinsic>& estimate) { estimate_ = estimate; }
  // Issue 21: the estimate's camera time offset (nullopt: points drawn where they were
  // captured), and the people's motion in the latest clusters (measured from the scans before it:
  // a live overlay cannot wait for the next one), so the points are drawn where they were when
  // the image was taken.
  void setTimeOffset(std::optional<double> time_offset_s) { time_offset_s_ = time_offset_s; }
  void setMotion(std::vector<PersonMotion> motion, double scan_stamp_s) {
    motion_ = std::move(motion);
    motion_stamp_s_ = scan_stamp_s;
  }

  void onImage(const sensor_msgs::Image::ConstPtr& image);  // renders and publishes
  void onMask(const sensor_msgs::Image::ConstPtr& mask);
  void onClusters(const sensor_msgs::PointCloud2::ConstPtr& clusters);

 private:
  void onCloud(const sensor_msgs::PointCloud2::ConstPtr& cloud);
  // Decode the cached message once (on first use after it arrived); an undecodable message
  // leaves the decoded value empty, as if it had not been received.
  const cv::Mat& decodedMask();
  const DecodedClusters& decodedClusters();
  void decodeCloud();

  void onOverlayConnection();  // (un)subscribes ~overlay_cloud with ~overlay's subscribers

  image_transport::ImageTransport it_;
  int max_points_;
  std::string clusters_topic_;
  ros::NodeHandle private_nh_;
  image_transport::Publisher publisher_;
  ros::Subscriber cloud_subscriber_;
  std::string cloud_topic_;  // resolved ~overlay_cloud, for messages
  std::unique_ptr<OverlayRenderer> renderer_;
  std::optional<Extrinsic> estimate_;
  std::optional<double> time_offset_s_;
  std::vector<PersonMotion> motion_;
  double motion_stamp_s_ = 0.0;
  sensor_msgs::Image::ConstPtr mask_msg_;
  cv::Mat mask_;  // decoded mask_msg_ (empty if it could not be decoded)
  bool mask_decoded_ = false;
  sensor_msgs::PointCloud2::ConstPtr clusters_msg_;
  DecodedClusters clusters_;  // decoded clusters_msg_ (empty if it could not be decoded)
  bool clusters_decoded_ = false;
  sensor_msgs::PointCloud2::ConstPtr cloud_msg_;
  std::vector<Eigen::Vector3f> cloud_points_;  // decoded cloud_msg_ (subsampled)
  bool cloud_decoded_ = false;
};

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
