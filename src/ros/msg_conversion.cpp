// Decoders: ROS messages -> core types. Every failure throws std::invalid_argument with one line
// naming the topic, what was wrong and what to do. (The encoders live in msg_encoding.cpp.)

#include "thermal_lidar_calibration/ros/msg_conversion.hpp"
#include "thermal_lidar_calibration/app/files/camera_calibration.hpp"

#include "cloud_fields.hpp"

#include <sensor_msgs/image_encodings.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>

namespace thermal_lidar_calibration {
namespace ros_io {
namespace {

using cloud_fields::CloudLayout;
using cloud_fields::checkCloudLayout;
using cloud_fields::checkedMul;
using cloud_fields::fail;
using cloud_fields::pointAt;
using cloud_fields::readScalar;

// No thermal camera comes near this; a larger declared size is a corrupt header, refused before
// cv::Mat's int dimensions or an allocation see it.
constexpr std::uint32_t kMaxImageSide = 1u << 15;

}  // namespace

cv::Mat decodeMonoImage(const sensor_msgs::Image& msg, const std::string& topic) {
  namespace enc = sensor_msgs::image_encodings;
  int cv_type = -1;
  std::size_t bytes_per_pixel = 0;
  if (msg.encoding == enc::MONO8 || msg.encoding == enc::TYPE_8UC1) {
    cv_type = CV_8UC1;
    bytes_per_pixel = 1;
  } else if (msg.encoding == enc::MONO16 || msg.encoding == enc::TYPE_16UC1) {
    cv_type = CV_16UC1;
    bytes_per_pixel = 2;
  } else {
    fail(topic, "image encoding '" + msg.encoding +
                    "' is not supported; publish mono8, 8UC1, mono16 or 16UC1 (one channel)");
  }
  if (msg.width == 0 || msg.height == 0) {
    fail(topic, "image is empty (" + std::to_string(msg.width) + "x" +
                    std::to_string(msg.height) + "); publish a non-empty image");
  }
  if (bytes_per_pixel == 2 && msg.is_bigendian) {
    fail(topic, "16-bit image is big-endian; publish little-endian data (is_bigendian = 0)");
  }
  if (msg.width > kMaxImageSide || msg.height > kMaxImageSide) {
    fail(topic, "image is " + std::to_string(msg.width) + "x" + std::to_string(msg.height) +
                    ", larger than " + std::to_string(kMaxImageSide) +
                    " pixels a side; the header is corrupt");
  }
  const std::size_t row_bytes = static_cast<std::size_t>(msg.width) * bytes_per_pixel;
  if (msg.step < row_bytes) {
    fail(topic, "image step " + std::to_string(msg.step) + " is smaller than width * " +
                    std::to_string(bytes_per_pixel) + " = " + std::to_string(row_bytes) +
                    "; fix the publisher's step");
  }
  // step * (height - 1) + row_bytes: both factors are below 2^32, but say so in the code.
  const auto rows_before_last = checkedMul(msg.step, msg.height - 1);
  if (!rows_before_last || msg.data.size() < *rows_before_last ||
      msg.data.size() - *rows_before_last < row_bytes) {
    fail(topic, "image data has " + std::to_string(msg.data.size()) + " bytes, expected " +
                    std::to_string(static_cast<std::size_t>(msg.step) * msg.height) +
                    " (step * height); the message is truncated");
  }
  cv::Mat out(static_cast<int>(msg.height), static_cast<int>(msg.width), cv_type);
  for (int r = 0; r < out.rows; ++r) {
    std::memcpy(out.ptr(r), msg.data.data() + static_cast<std::size_t>(r) * msg.step, row_bytes);
  }
  return out;
}

DecodedClusters decodeClusters(const sensor_msgs::PointCloud2& msg, const std::string& topic,
                               const PointTimeField& time_field) {
  const CloudLayout layout = checkCloudLayout(msg, topic, /*need_label=*/true);
  const sensor_msgs::PointField* time = cloud_fields::pointTimeField(msg, time_field, topic);
  std::optional<cloud_fields::PointTimeReader> times;
  if (time) times.emplace(*time, msg.header.stamp.toSec());
  // A dataset bag's clusters carry their people's measured motion (velocity_fields.hpp).
  const sensor_msgs::PointField* velocity[3] = {cloud_fields::findField(msg, kVelocityFields[0]),
                                                 cloud_fields::findField(msg, kVelocityFields[1]),
                                                 cloud_fields::findField(msg, kVelocityFields[2])};
  const bool moving = velocity[0] && velocity[1] && velocity[2];
  if (moving) {
    for (const sensor_msgs::PointField* f : velocity) cloud_fields::checkFieldFits(msg, *f, topic);
  }
  const sensor_msgs::PointField* velocity_se[2] = {cloud_fields::findField(msg, kVelocityErrorFields[0]),
                                                    cloud_fields::findField(msg, kVelocityErrorFields[1])};
  const bool with_errors = moving && velocity_se[0] && velocity_se[1];
  if (with_errors) {
    for (const sensor_msgs::PointField* f : velocity_se) cloud_fields::checkFieldFits(msg, *f, topic);
  }
  DecodedClusters out;
  out.points.reserve(layout.points);  // bounded: the data holds every point (checked)
  out.labels.reserve(layout.points);
  if (times) out.point_time_s.reserve(layout.points);
  if (moving) out.point_velocity.reserve(layout.points);
  if (with_errors) out.point_velocity_se.reserve(layout.points);
  for (std::size_t i = 0; i < layout.points; ++i) {
    const std::uint8_t* p = pointAt(msg, i);
    const double x = readScalar(p + layout.axes[0]->offset, layout.axes[0]->datatype);
    const double y = readScalar(p + layout.axes[1]->offset, layout.axes[1]->datatype);
    const double z = readScalar(p + layout.axes[2]->offset, layout.axes[2]->datatype);
    const double l = readScalar(p + layout.label->offset, layout.label->datatype);
    // A point without a usable time goes with its time: points and times stay aligned.
    const double t = times ? times->secondsFromStamp(p) : 0.0;
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z) || !std::isfinite(l) || !std::isfinite(t)) {
      ++out.nonfinite_dropped;
      continue;
    }
    const float xf = static_cast<float>(x), yf = static_cast<float>(y), zf = static_cast<float>(z);
    if (!std::isfinite(xf) || !std::isfinite(yf) || !std::isfinite(zf)) {
      ++out.nonfinite_dropped;  // float64 beyond the float32 range
      continue;
    }
    if (l != std::round(l) || l < std::numeric_limits<std::int32_t>::min() ||
        l > std::numeric_limits<std::int32_t>::max()) {
      std::ostringstream value;
      value << l;
      fail(topic, "PointCloud2 label " + value.str() +
                      " is not an int32 integer; publish one integer label per person");
    }
    out.points.emplace_back(xf, yf, zf);
    out.labels.push_back(static_cast<std::int32_t>(l));
    if (times) out.point_time_s.push_back(static_cast<float>(t));
    if (moving) {
      Eigen::Vector3f v;
      for (int k = 0; k < 3; ++k) v[k] = static_cast<float>(readScalar(p + velocity[k]->offset, velocity[k]->datatype));
      out.point_velocity.push_back(v.allFinite() ? v : Eigen::Vector3f::Zero());  // not finite: not measured
    }
    if (with_errors) {
      Eigen::Vector2f se;
      for (int k = 0; k < 2; ++k) {
        se[k] = static_cast<float>(readScalar(p + velocity_se[k]->offset, velocity_se[k]->datatype));
      }
      out.point_velocity_se.push_back(se);
    }
  }
  return out;
}

DecodedCloud decodeCloud(const sensor_msgs::PointCloud2& msg, const std::string& topic) {
  const CloudLayout layout = checkCloudLayout(msg, topic, /*need_label=*/false);
  if (layout.points > std::numeric_limits<std::uint32_t>::max()) {
    fail(topic, "PointCloud2 has " + std::to_string(layout.points) + " points, more than a scan can; fix the publisher");
  }
  DecodedCloud out;
  out.points.reserve(layout.points);
  out.source_index.reserve(layout.points);
  for (std::size_t i = 0; i < layout.points; ++i) {
    const std::uint8_t* p = pointAt(msg, i);
    const float x = static_cast<float>(readScalar(p + layout.axes[0]->offset, layout.axes[0]->datatype));
    const float y = static_cast<float>(readScalar(p + layout.axes[1]->offset, layout.axes[1]->datatype));
    const float z = static_cast<float>(readScalar(p + layout.axes[2]->offset, layout.axes[2]->datatype));
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) continue;
    out.points.emplace_back(x, y, z);
    out.source_index.push_back(static_cast<std::uint32_t>(i));
  }
  return out;
}

std::vector<Eigen::Vector3f> decodeCloudPoints(const sensor_msgs::PointCloud2& msg,
                                               const std::string& topic, std::size_t max_points) {
  const CloudLayout layout = checkCloudLayout(msg, topic, /*need_label=*/false);
  std::vector<Eigen::Vector3f> out;
  if (layout.points == 0 || max_points == 0) return out;
  // Every stride-th point: the work is bounded by max_points, not by the cloud's size.
  const std::size_t stride = std::max<std::size_t>(1, layout.points / max_points);
  out.reserve(std::min(layout.points, max_points + 1));
  for (std::size_t i = 0; i < layout.points; i += stride) {
    const std::uint8_t* p = pointAt(msg, i);
    const float x = static_cast<float>(readScalar(p + layout.axes[0]->offset, layout.axes[0]->datatype));
    const float y = static_cast<float>(readScalar(p + layout.axes[1]->offset, layout.axes[1]->datatype));
    const float z = static_cast<float>(readScalar(p + layout.axes[2]->offset, layout.axes[2]->datatype));
    if (std::isfinite(x) && std::isfinite(y) && std::isfinite(z)) out.emplace_back(x, y, z);
  }
  return out;
}

CameraModel cameraModelFromMsg(const sensor_msgs::CameraInfo& msg) {
  CameraCalibration calibration;
  calibration.width = msg.width;
  calibration.height = msg.height;
  std::copy(msg.K.begin(), msg.K.end(), calibration.K.begin());
  calibration.distortion_model = msg.distortion_model;
  calibration.D.assign(msg.D.begin(), msg.D.end());
  try {
    return cameraModelFromCalibration(calibration);  // the same rules as a camera_info file
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("CameraInfo: ") + e.what());
  }
}

std::string tfFrameId(const std::string& frame_id) {
  const std::size_t first = frame_id.find_first_not_of('/');
  return first == std::string::npos ? "" : frame_id.substr(first);
}

ScanPeople decodeScanPeople(const sensor_msgs::PointCloud2& msg, const std::string& topic,
                            const PointTimeField& time_field) {
  const DecodedClusters decoded = decodeClusters(msg, topic, time_field);
  return summariseScan(msg.header.stamp.toSec(), decoded.points, decoded.labels, decoded.point_time_s);
}

Frame decodeFrame(const sensor_msgs::Image& image, const sensor_msgs::Image& mask,
                  const sensor_msgs::PointCloud2& clusters, const std::string& image_topic,
                  const std::string& mask_topic, const std::string& clusters_topic,
                  const PointTimeField& time_field) {
  Frame frame;
  frame.stamp_s = image.header.stamp.toSec();
  frame.camera_frame =
      tfFrameId(image.header.frame_id.empty() ? mask.header.frame_id : image.header.frame_id);
  frame.lidar_frame = tfFrameId(clusters.header.frame_id);
  frame.image = decodeMonoImage(image, image_topic);
  frame.mask = decodeMonoImage(mask, mask_topic);
  if (frame.image.size() != frame.mask.size()) {
    fail(mask_topic, "mask is " + std::to_string(frame.mask.cols) + "x" +
                         std::to_string(frame.mask.rows) + " but the image on " + image_topic +
                         " is " + std::to_string(frame.image.cols) + "x" +
                         std::to_string(frame.image.rows) +
                         "; segment the same image the camera publishes");
  }
  DecodedClusters decoded = decodeClusters(clusters, clusters_topic, time_field);
  frame.points = std::move(decoded.points);
  frame.labels = std::move(decoded.labels);
  frame.point_time_s = std::move(decoded.point_time_s);
  frame.motion = motionFromFields(frame.labels, decoded.point_velocity, decoded.point_velocity_se);
  frame.point_velocity = std::move(decoded.point_velocity);
  frame.cloud_stamp_s = clusters.header.stamp.toSec();
  frame.nonfinite_points_dropped = decoded.nonfinite_dropped;
  return frame;
}

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
