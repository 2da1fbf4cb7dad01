#include "thermal_lidar_calibration/ros/person_detection_adapter.hpp"

#include "thermal_lidar_calibration/ros/msg_conversion.hpp"

#include "cloud_fields.hpp"

#include <boost/make_shared.hpp>
#include <cv_bridge/cv_bridge.h>
#include <sensor_msgs/image_encodings.h>
#include <sensor_msgs/point_cloud2_iterator.h>

#include <algorithm>
#include <cstring>
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
  // Every finite point, through the one validated cloud decoder (sizes checked, overflow-safe).
  const DecodedCloud decoded = decodeCloud(cloud, topic);
  DetectedCloud out;
  out.detection = lidar_.detect(decoded.points);
  // The person points keep the scan's other fields, so their per-point times reach the ingest
  // path whatever the field is called (point_time_field there decides which to read). Only the
  // person points are copied: a few thousand at most, against the scan's 50-100k.
  std::vector<std::uint32_t> source_index;
  source_index.reserve(out.detection.indices.size());
  for (const int i : out.detection.indices) source_index.push_back(decoded.source_index[static_cast<std::size_t>(i)]);
  out.clusters = encodeLabelledPoints(out.detection.points, out.detection.labels, cloud, source_index);
  return out;
}

namespace {

// float32 x, y, z + uint32 label at offsets 0, 4, 8, 12 of each `point_step`-byte point.
sensor_msgs::PointCloud2::Ptr xyzLabelCloud(const std::vector<Eigen::Vector3f>& points,
                                            const std::vector<std::uint32_t>& labels,
                                            std::vector<sensor_msgs::PointField> extra_fields,
                                            std::uint32_t point_step) {
  if (points.size() != labels.size()) {
    throw std::invalid_argument("encodeLabelledPoints: one label per point");
  }
  auto msg = boost::make_shared<sensor_msgs::PointCloud2>();
  sensor_msgs::PointCloud2Modifier modifier(*msg);
  modifier.setPointCloud2Fields(4, "x", 1, sensor_msgs::PointField::FLOAT32, "y", 1,
                                sensor_msgs::PointField::FLOAT32, "z", 1,
                                sensor_msgs::PointField::FLOAT32, "label", 1,
                                sensor_msgs::PointField::UINT32);
  for (auto& f : extra_fields) msg->fields.push_back(std::move(f));
  msg->point_step = std::max(msg->point_step, point_step);
  msg->height = 1;
  msg->width = static_cast<std::uint32_t>(points.size());
  msg->row_step = msg->point_step * msg->width;
  msg->is_bigendian = false;
  msg->is_dense = true;
  msg->data.assign(static_cast<std::size_t>(msg->row_step), 0);
  for (std::size_t i = 0; i < points.size(); ++i) {
    std::uint8_t* p = msg->data.data() + i * msg->point_step;
    std::memcpy(p, points[i].data(), 12);
    std::memcpy(p + 12, &labels[i], 4);
  }
  return msg;
}

}  // namespace

sensor_msgs::PointCloud2::Ptr encodeLabelledPoints(const std::vector<Eigen::Vector3f>& points,
                                                   const std::vector<std::uint32_t>& labels,
                                                   const std_msgs::Header& header) {
  auto msg = xyzLabelCloud(points, labels, {}, 16);
  msg->header = header;
  return msg;
}

sensor_msgs::PointCloud2::Ptr encodeLabelledPoints(const std::vector<Eigen::Vector3f>& points,
                                                   const std::vector<std::uint32_t>& labels,
                                                   const sensor_msgs::PointCloud2& source,
                                                   const std::vector<std::uint32_t>& source_index) {
  if (source_index.size() != points.size()) {
    throw std::invalid_argument("encodeLabelledPoints: one source index per point");
  }
  // The other fields after x, y, z, label, each aligned to its own size.
  struct Copy {
    std::uint32_t from, to, bytes;
  };
  std::vector<sensor_msgs::PointField> extra;
  std::vector<Copy> copies;
  std::uint32_t step = 16;
  for (const sensor_msgs::PointField& f : source.fields) {
    if (f.name == "x" || f.name == "y" || f.name == "z" || f.name == "label") continue;
    const std::size_t size = cloud_fields::datatypeSize(f.datatype);
    const std::size_t bytes = size * std::max<std::uint32_t>(f.count, 1);
    if (size == 0 || f.offset + bytes > source.point_step) continue;
    step = static_cast<std::uint32_t>((step + size - 1) / size * size);
    sensor_msgs::PointField out = f;
    out.offset = step;
    extra.push_back(out);
    copies.push_back({f.offset, step, static_cast<std::uint32_t>(bytes)});
    step += static_cast<std::uint32_t>(bytes);
  }
  step = (step + 3) / 4 * 4;
  auto msg = xyzLabelCloud(points, labels, std::move(extra), step);
  msg->header = source.header;
  const std::size_t source_points = static_cast<std::size_t>(source.width) * source.height;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (source_index[i] >= source_points) throw std::invalid_argument("encodeLabelledPoints: source index out of range");
    const std::uint8_t* from = cloud_fields::pointAt(source, source_index[i]);
    std::uint8_t* to = msg->data.data() + i * msg->point_step;
    for (const Copy& c : copies) std::memcpy(to + c.to, from + c.from, c.bytes);
  }
  return msg;
}

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
