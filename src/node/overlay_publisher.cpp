// ~overlay publisher: caches inputs, renders with OverlayRenderer when subscribed.

#include "thermal_lidar_calibration/node/overlay_publisher.hpp"

#include "thermal_lidar_calibration/core/person_timing.hpp"

#include "thermal_lidar_calibration/ros/msg_conversion.hpp"

#include <cv_bridge/cv_bridge.h>
#include <ros/console.h>

#include <algorithm>
#include <stdexcept>

namespace thermal_lidar_calibration {
namespace ros_io {

OverlayPublisher::OverlayPublisher(ros::NodeHandle& private_nh, int max_points,
                                   std::string clusters_topic)
    : it_(private_nh), max_points_(max_points), clusters_topic_(std::move(clusters_topic)),
      private_nh_(private_nh) {
  const image_transport::SubscriberStatusCallback changed =
      [this](const image_transport::SingleSubscriberPublisher&) { onOverlayConnection(); };
  publisher_ = it_.advertise("overlay", 1, changed, changed);
  cloud_topic_ = private_nh_.resolveName("overlay_cloud");
}

void OverlayPublisher::onOverlayConnection() {
  if (publisher_.getNumSubscribers() > 0 && !cloud_subscriber_) {
    cloud_subscriber_ = private_nh_.subscribe("overlay_cloud", 1, &OverlayPublisher::onCloud, this);
  } else if (publisher_.getNumSubscribers() == 0 && cloud_subscriber_) {
    cloud_subscriber_.shutdown();
    cloud_subscriber_ = ros::Subscriber();
    cloud_msg_.reset();  // a stale cloud must not be drawn when someone looks again
  }
}

void OverlayPublisher::setCamera(const CameraModel& camera) {
  renderer_ = std::make_unique<OverlayRenderer>(camera, max_points_);
}

void OverlayPublisher::onMask(const sensor_msgs::Image::ConstPtr& mask) {
  mask_msg_ = mask;
  mask_decoded_ = false;
  mask_.release();
}

void OverlayPublisher::onClusters(const sensor_msgs::PointCloud2::ConstPtr& clusters) {
  clusters_msg_ = clusters;
  clusters_decoded_ = false;
  clusters_ = DecodedClusters();
}

void OverlayPublisher::onCloud(const sensor_msgs::PointCloud2::ConstPtr& cloud) {
  cloud_msg_ = cloud;
  cloud_decoded_ = false;
}

const cv::Mat& OverlayPublisher::decodedMask() {
  if (!mask_decoded_) {
    try {
      mask_ = decodeMonoImage(*mask_msg_, "thermal/human_mask");
    } catch (const std::invalid_argument&) {
      mask_.release();  // the ingest path reports bad masks
    }
    mask_decoded_ = true;
  }
  return mask_;
}

const DecodedClusters& OverlayPublisher::decodedClusters() {
  if (!clusters_decoded_) {
    try {
      clusters_ = decodeClusters(*clusters_msg_, clusters_topic_);
    } catch (const std::invalid_argument&) {
      clusters_ = DecodedClusters();  // the ingest path reports bad clusters
    }
    clusters_decoded_ = true;
  }
  return clusters_;
}

void OverlayPublisher::decodeCloud() {
  if (cloud_decoded_) return;
  cloud_decoded_ = true;
  cloud_points_.clear();
  try {
    // The ingest path's cloud check, then at most ~max_points_ points read.
    cloud_points_ = decodeCloudPoints(*cloud_msg_, cloud_topic_,
                                      static_cast<std::size_t>(std::max(1, max_points_)));
  } catch (const std::invalid_argument& e) {
    ROS_WARN_THROTTLE(10.0, "%s; the overlay is drawn without it", e.what());
  }
}

// Every input is decoded at most once per message (cached until the next one arrives); the
// renderer only reads the shared mask data.
void OverlayPublisher::onImage(const sensor_msgs::Image::ConstPtr& image) {
  if (!renderer_ || publisher_.getNumSubscribers() == 0) return;
  OverlayInput input;
  try {
    input.thermal = decodeMonoImage(*image, "thermal/image_raw");
  } catch (const std::invalid_argument&) {
    return;  // the ingest path reports bad images
  }
  if (mask_msg_ && mask_msg_->width == image->width && mask_msg_->height == image->height) {
    input.mask = decodedMask();  // shares the cached pixels (no copy)
  }
  if (estimate_) {
    input.estimate = &*estimate_;
    if (clusters_msg_) {
      const DecodedClusters& decoded = decodedClusters();
      input.cluster_points = decoded.points;
      input.cluster_labels = decoded.labels;
      const double cloud_stamp = clusters_msg_->header.stamp.toSec();
      if (time_offset_s_ && !motion_.empty() && motion_stamp_s_ == cloud_stamp) {
        CalibrationPair at;  // the clusters seen from the image's instant
        at.stamp_s = image->header.stamp.toSec();
        at.cloud_stamp_s = cloud_stamp;
        at.points = decoded.points;
        at.labels = decoded.labels;
        at.point_time_s = decoded.point_time_s;
        attachMotion(at, motion_);
        input.cluster_points = pointsAtImageTime(at, *time_offset_s_);
      }
    }
    if (cloud_msg_) decodeCloud();
    input.cloud_points = &cloud_points_;
  }
  const cv::Mat bgr = renderer_->render(input);
  publisher_.publish(cv_bridge::CvImage(image->header, "bgr8", bgr).toImageMsg());
}

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
