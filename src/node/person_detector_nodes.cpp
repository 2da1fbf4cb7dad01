// The person detector nodes: see include/thermal_lidar_calibration/node/person_detector_nodes.hpp.

#include "thermal_lidar_calibration/node/person_detector_nodes.hpp"

#include "thermal_lidar_calibration/detection/detection_views.hpp"
#include "thermal_lidar_calibration/ros/msg_conversion.hpp"
#include "thermal_lidar_calibration/ros/node_parameter_source.hpp"

#include <cv_bridge/cv_bridge.h>
#include <visualization_msgs/MarkerArray.h>

#include <sstream>
#include <stdexcept>

namespace thermal_lidar_calibration {
namespace ros_io {

DetectionParameters loadDetectionParametersOf(const ros::NodeHandle& private_nh, const char* node) {
  const DetectionParameters p = loadDetectionParameters(*makeNodeHandleParameterSource(private_nh));
  std::ostringstream s;
  for (const auto& kv : describeDetectionParameters(p)) s << "\n  " << kv.first << ": " << kv.second;
  ROS_INFO("%s: effective parameters:%s", node, s.str().c_str());
  return p;
}

ThermalPersonSegmenterNode::ThermalPersonSegmenterNode(ros::NodeHandle nh, ros::NodeHandle private_nh)
    : nh_(std::move(nh)),
      private_nh_(std::move(private_nh)),
      adapter_(std::make_unique<PersonDetectionAdapter>(
          loadDetectionParametersOf(private_nh_, "thermal_person_segmenter"))),
      it_(nh_),
      private_it_(private_nh_) {
  image_topic_ = nh_.resolveName("thermal/image_raw");
  mask_pub_ = it_.advertise("thermal/human_mask", 5);
  if (adapter_->parameters().input_flip != detection::ImageFlip::kNone) {
    upright_pub_ = it_.advertise("thermal/image_upright", 5);
  }
  debug_pub_ = private_it_.advertise("debug_image", 1);
  image_sub_ = it_.subscribe("thermal/image_raw", 5, &ThermalPersonSegmenterNode::onImage, this);
  ROS_INFO("thermal_person_segmenter: %s -> %s (flip %s)", image_topic_.c_str(),
           nh_.resolveName("thermal/human_mask").c_str(),
           detection::toString(adapter_->parameters().input_flip));
}

void ThermalPersonSegmenterNode::onImage(const sensor_msgs::Image::ConstPtr& image) {
  try {
    const SegmentedImage seg = adapter_->segment(image, image_topic_);
    mask_pub_.publish(seg.mask);
    if (upright_pub_) upright_pub_.publish(seg.image);
    if (debug_pub_.getNumSubscribers() > 0) {  // drawn only while someone looks
      const cv::Mat pixels = decodeMonoImage(*seg.image, image_topic_);
      debug_pub_.publish(cv_bridge::CvImage(image->header, "bgr8",
                                            detection::renderMaskOverlay(pixels, seg.segmentation))
                             .toImageMsg());
    }
  } catch (const std::exception& e) {
    if (const auto held_back = throttle_.admit(e.what())) {
      ROS_ERROR("%s: %s; frame skipped%s", image_topic_.c_str(), e.what(),
                throttle_.heldBackText(*held_back).c_str());
    }
  }
}

LidarPersonDetectorNode::LidarPersonDetectorNode(ros::NodeHandle nh, ros::NodeHandle private_nh)
    : nh_(std::move(nh)),
      private_nh_(std::move(private_nh)),
      adapter_(std::make_unique<PersonDetectionAdapter>(
          loadDetectionParametersOf(private_nh_, "lidar_person_detector"))) {
  cloud_topic_ = nh_.resolveName("lidar/points");
  clusters_pub_ = nh_.advertise<sensor_msgs::PointCloud2>("lidar/human_clusters", 5);
  markers_pub_ = private_nh_.advertise<visualization_msgs::MarkerArray>("markers", 1);
  cloud_sub_ = nh_.subscribe("lidar/points", 2, &LidarPersonDetectorNode::onCloud, this);
  ROS_INFO("lidar_person_detector: %s -> %s", cloud_topic_.c_str(),
           nh_.resolveName("lidar/human_clusters").c_str());
}

void LidarPersonDetectorNode::onCloud(const sensor_msgs::PointCloud2::ConstPtr& cloud) {
  try {
    const DetectedCloud out = adapter_->detect(*cloud, cloud_topic_);
    clusters_pub_.publish(out.clusters);
    if (markers_pub_.getNumSubscribers() == 0) return;
    visualization_msgs::MarkerArray markers;
    visualization_msgs::Marker clear;
    clear.action = visualization_msgs::Marker::DELETEALL;
    markers.markers.push_back(clear);
    for (const detection::LidarPerson& p : out.detection.people) {
      visualization_msgs::Marker box;
      box.header = cloud->header;
      box.ns = "people";
      box.id = static_cast<int>(p.label);
      box.type = visualization_msgs::Marker::CUBE;
      box.pose.position.x = p.centroid.x();
      box.pose.position.y = p.centroid.y();
      box.pose.position.z = p.centroid.z();
      box.pose.orientation.w = 1.0;
      box.scale.x = std::max(0.05f, p.size.x());
      box.scale.y = std::max(0.05f, p.size.y());
      box.scale.z = std::max(0.05f, p.size.z());
      box.color.r = 1.0f;
      box.color.g = 0.4f;
      box.color.a = 0.5f;
      box.lifetime = ros::Duration(0.5);
      markers.markers.push_back(box);
      visualization_msgs::Marker text = box;
      text.ns = "sizes";
      text.type = visualization_msgs::Marker::TEXT_VIEW_FACING;
      text.pose.position.z += 0.5 * box.scale.z + 0.3;
      text.scale.x = text.scale.y = 0.0;
      text.scale.z = 0.3;
      text.color.r = text.color.g = text.color.b = text.color.a = 1.0f;
      char label[96];
      std::snprintf(label, sizeof(label), "%u: %.2f m tall, %.1f m, %d pts", p.label, p.height_m,
                    p.range_m, p.point_count);
      text.text = label;
      markers.markers.push_back(text);
    }
    markers_pub_.publish(markers);
  } catch (const std::exception& e) {
    if (const auto held_back = throttle_.admit(e.what())) {
      ROS_ERROR("%s: %s; scan skipped%s", cloud_topic_.c_str(), e.what(),
                throttle_.heldBackText(*held_back).c_str());
    }
  }
}

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
