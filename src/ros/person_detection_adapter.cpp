#include "thermal_lidar_calibration/ros/person_detection_adapter.hpp"

#include "thermal_lidar_calibration/ros/msg_conversion.hpp"

#include <boost/make_shared.hpp>
#include <cv_bridge/cv_bridge.h>
#include <sensor_msgs/image_encodings.h>
#include <sensor_msgs/point_cloud2_iterator.h>

#include <limits>
#include <stdexcept>

namespace thermal_lidar_calibration {
namespace ros_io {

PersonDetectionAdapter::PersonDetectionAdapter(const DetectionParameters& params)
    : params_(params), segmenter_(params.thermal), person_size_(params.thermal), lidar_(params.lidar) {}

SegmentedImage PersonDetectionAdapter::segment(const sensor_msgs::Image::ConstPtr& image,
                                               const std::string& topic) {
  SegmentedImage out;
  cv::Mat pixels = decodeMonoImage(*image, topic);  // throws invalid_argument naming the topic
  if (params_.input_flip == detection::ImageFlip::kNone) {
    out.image = image;
  } else {
    pixels = detection::flipImage(pixels, params_.input_flip);
    auto flipped = cv_bridge::CvImage(image->header, image->encoding, pixels).toImageMsg();
    out.image = flipped;
  }
  out.segmentation = segmenter_.segment(pixels);
  detection::applySizeCheck(out.segmentation, person_size_);
  out.mask = cv_bridge::CvImage(image->header, sensor_msgs::image_encodings::MONO8,
                                out.segmentation.mask)
                 .toImageMsg();
  return out;
}

DetectedCloud PersonDetectionAdapter::detect(const sensor_msgs::PointCloud2& cloud,
                                             const std::string& topic) {
  // Every point, through the one validated cloud decoder (sizes checked, overflow-safe).
  const std::vector<Eigen::Vector3f> points =
      decodeCloudPoints(cloud, topic, std::numeric_limits<std::size_t>::max() / 2);
  DetectedCloud out;
  out.detection = lidar_.detect(points);
  out.clusters = encodeLabelledPoints(out.detection.points, out.detection.labels, cloud.header);
  return out;
}

sensor_msgs::PointCloud2::Ptr encodeLabelledPoints(const std::vector<Eigen::Vector3f>& points,
                                                   const std::vector<std::uint32_t>& labels,
                                                   const std_msgs::Header& header) {
  if (points.size() != labels.size()) {
    throw std::invalid_argument("encodeLabelledPoints: one label per point");
  }
  auto msg = boost::make_shared<sensor_msgs::PointCloud2>();
  msg->header = header;
  sensor_msgs::PointCloud2Modifier modifier(*msg);
  modifier.setPointCloud2Fields(4, "x", 1, sensor_msgs::PointField::FLOAT32, "y", 1,
                                sensor_msgs::PointField::FLOAT32, "z", 1,
                                sensor_msgs::PointField::FLOAT32, "label", 1,
                                sensor_msgs::PointField::UINT32);
  modifier.resize(points.size());
  msg->height = 1;
  msg->width = static_cast<std::uint32_t>(points.size());
  msg->is_dense = true;
  sensor_msgs::PointCloud2Iterator<float> x(*msg, "x"), y(*msg, "y"), z(*msg, "z");
  sensor_msgs::PointCloud2Iterator<std::uint32_t> label(*msg, "label");
  for (std::size_t i = 0; i < points.size(); ++i, ++x, ++y, ++z, ++label) {
    *x = points[i].x();
    *y = points[i].y();
    *z = points[i].z();
    *label = labels[i];
  }
  return msg;
}

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
