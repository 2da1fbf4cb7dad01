#pragma once
// The two person detectors as ROS nodes (and nodelets: src/node/person_detector_nodelets.cpp),
// thin adapters over PersonDetectionAdapter, the code calibrate_bag --detect runs:
//
//   ThermalPersonSegmenterNode  thermal/image_raw -> thermal/human_mask (mono8, same header and
//                               size); with ~thermal_input_flip also thermal/image_upright (the
//                               image it segmented); ~debug_image (bgr8) while subscribed
//   LidarPersonDetectorNode     lidar/points -> lidar/human_clusters (x, y, z, uint32 label, same
//                               header); ~markers (visualization_msgs/MarkerArray: a box per
//                               person with its size) while subscribed
//
// Parameters: the detection keys of config/default.yaml (~key), checked at start (one line and
// the node does not start). A message the detector cannot read gives a throttled one-line error
// naming the topic (one line per kind of fault and period, counting the rest); the node stays up.

#include "thermal_lidar_calibration/app/runtime/fault_throttle.hpp"
#include "thermal_lidar_calibration/ros/person_detection_adapter.hpp"

#include <image_transport/image_transport.h>
#include <ros/ros.h>

#include <memory>
#include <string>

namespace thermal_lidar_calibration {
namespace ros_io {

class ThermalPersonSegmenterNode {
 public:
  ThermalPersonSegmenterNode(ros::NodeHandle nh, ros::NodeHandle private_nh);  // throws on bad params

 private:
  void onImage(const sensor_msgs::Image::ConstPtr& image);

  ros::NodeHandle nh_, private_nh_;
  std::unique_ptr<PersonDetectionAdapter> adapter_;
  image_transport::ImageTransport it_, private_it_;
  image_transport::Subscriber image_sub_;
  image_transport::Publisher mask_pub_, upright_pub_, debug_pub_;
  std::string image_topic_;
  FaultThrottle throttle_{5.0};
};

class LidarPersonDetectorNode {
 public:
  LidarPersonDetectorNode(ros::NodeHandle nh, ros::NodeHandle private_nh);  // throws on bad params

 private:
  void onCloud(const sensor_msgs::PointCloud2::ConstPtr& cloud);

  ros::NodeHandle nh_, private_nh_;
  std::unique_ptr<PersonDetectionAdapter> adapter_;
  ros::Subscriber cloud_sub_;
  ros::Publisher clusters_pub_, markers_pub_;
  std::string cloud_topic_;
  FaultThrottle throttle_{5.0};
};

// Loads the detection keys of `private_nh` and logs the effective values (throws
// std::invalid_argument naming the key on a bad one).
DetectionParameters loadDetectionParametersOf(const ros::NodeHandle& private_nh, const char* node);

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
