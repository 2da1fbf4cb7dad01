// Decoders: ROS messages -> core types. Every failure throws std::invalid_argument with one line
// naming the topic, what was wrong and what to do. (The encoders live in msg_encoding.cpp.)

#include "thermal_lidar_calibration/ros/msg_conversion.hpp"
#include "thermal_lidar_calibration/app/camera_calibration.hpp"

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

// No thermal camera comes near this; a larger declared size is a corrupt header, refused before
// cv::Mat's int dimensions or an allocation see it.
constexpr std::uint32_t kMaxImageSide = 1u << 15;

std::string topicPrefix(const std::string& topic) {
  return topic.empty() ? std::string() : topic + ": ";
}

[[noreturn]] void fail(const std::string& topic, const std::string& what) {
  throw std::invalid_argument(topicPrefix(topic) + what);
}

const char* datatypeName(std::uint8_t datatype) {
  switch (datatype) {
    case sensor_msgs::PointField::INT8: return "int8";
    case sensor_msgs::PointField::UINT8: return "uint8";
    case sensor_msgs::PointField::INT16: return "int16";
    case sensor_msgs::PointField::UINT16: return "uint16";
    case sensor_msgs::PointField::INT32: return "int32";
    case sensor_msgs::PointField::UINT32: return "uint32";
    case sensor_msgs::PointField::FLOAT32: return "float32";
    case sensor_msgs::PointField::FLOAT64: return "float64";
    default: return "unknown";
  }
}

std::size_t datatypeSize(std::uint8_t datatype) {
  switch (datatype) {
    case sensor_msgs::PointField::INT8:
    case sensor_msgs::PointField::UINT8: return 1;
    case sensor_msgs::PointField::INT16:
    case sensor_msgs::PointField::UINT16: return 2;
    case sensor_msgs::PointField::INT32:
    case sensor_msgs::PointField::UINT32:
    case sensor_msgs::PointField::FLOAT32: return 4;
    case sensor_msgs::PointField::FLOAT64: return 8;
    default: return 0;
  }
}

// Reads one scalar of `datatype` at `p` (little-endian host assumed, as checked by the caller).
double readScalar(const std::uint8_t* p, std::uint8_t datatype) {
  switch (datatype) {
    case sensor_msgs::PointField::INT8: { std::int8_t v; std::memcpy(&v, p, 1); return v; }
    case sensor_msgs::PointField::UINT8: return *p;
    case sensor_msgs::PointField::INT16: { std::int16_t v; std::memcpy(&v, p, 2); return v; }
    case sensor_msgs::PointField::UINT16: { std::uint16_t v; std::memcpy(&v, p, 2); return v; }
    case sensor_msgs::PointField::INT32: { std::int32_t v; std::memcpy(&v, p, 4); return v; }
    case sensor_msgs::PointField::UINT32: { std::uint32_t v; std::memcpy(&v, p, 4); return v; }
    case sensor_msgs::PointField::FLOAT32: { float v; std::memcpy(&v, p, 4); return v; }
    case sensor_msgs::PointField::FLOAT64: { double v; std::memcpy(&v, p, 8); return v; }
    default: return std::numeric_limits<double>::quiet_NaN();
  }
}

std::string fieldList(const sensor_msgs::PointCloud2& msg) {
  if (msg.fields.empty()) return "none";
  std::string out;
  for (const auto& f : msg.fields) out += (out.empty() ? "" : ", ") + f.name;
  return out;
}

const sensor_msgs::PointField* findField(const sensor_msgs::PointCloud2& msg,
                                         const std::string& name) {
  for (const auto& f : msg.fields) {
    if (f.name == name) return &f;
  }
  return nullptr;
}

// a * b, or nullopt when it does not fit in size_t: declared sizes come from the wire.
std::optional<std::size_t> checkedMul(std::size_t a, std::size_t b) {
  std::size_t out = 0;
  if (__builtin_mul_overflow(a, b, &out)) return std::nullopt;
  return out;
}

void checkFieldFits(const sensor_msgs::PointCloud2& msg, const sensor_msgs::PointField& f,
                    const std::string& topic) {
  const std::size_t size = datatypeSize(f.datatype);
  if (size == 0) {
    fail(topic, "PointCloud2 field '" + f.name + "' has unknown datatype " +
                    std::to_string(f.datatype) + "; use a sensor_msgs/PointField datatype");
  }
  if (static_cast<std::size_t>(f.offset) + size > msg.point_step) {
    fail(topic, "PointCloud2 field '" + f.name + "' (offset " + std::to_string(f.offset) +
                    ", " + datatypeName(f.datatype) + ") lies outside point_step " +
                    std::to_string(msg.point_step) + "; fix the publisher's field layout");
  }
}

// A PointCloud2 whose layout was checked: x, y, z (float32 or float64) and, when asked for,
// `label`, every field inside point_step, and row_step and data large enough for
// width x height points, every size computed without overflow. The one check every cloud
// decoder (clusters of the ingest path, ~overlay_cloud) goes through.
struct CloudLayout {
  const sensor_msgs::PointField* axes[3] = {nullptr, nullptr, nullptr};
  const sensor_msgs::PointField* label = nullptr;
  std::size_t points = 0;  // width * height
};

CloudLayout checkCloudLayout(const sensor_msgs::PointCloud2& msg, const std::string& topic,
                             bool need_label) {
  if (msg.is_bigendian) {
    fail(topic, "PointCloud2 is big-endian; publish little-endian data (is_bigendian = false)");
  }
  CloudLayout layout;
  const char* axis_names[3] = {"x", "y", "z"};
  for (int k = 0; k < 3; ++k) {
    layout.axes[k] = findField(msg, axis_names[k]);
    if (!layout.axes[k]) {
      fail(topic, std::string("PointCloud2 has no '") + axis_names[k] + "' field (fields: " +
                      fieldList(msg) + "); publish float32 x, y, z");
    }
    if (layout.axes[k]->datatype != sensor_msgs::PointField::FLOAT32 &&
        layout.axes[k]->datatype != sensor_msgs::PointField::FLOAT64) {
      fail(topic, std::string("PointCloud2 field '") + axis_names[k] + "' is " +
                      datatypeName(layout.axes[k]->datatype) + "; publish float32 x, y, z");
    }
    checkFieldFits(msg, *layout.axes[k], topic);
  }
  if (need_label) {
    layout.label = findField(msg, "label");
    if (!layout.label) {
      fail(topic, "PointCloud2 has no 'label' field (fields: " + fieldList(msg) +
                      "); publish one integer label per person");
    }
    if (layout.label->datatype == sensor_msgs::PointField::FLOAT64 ||
        datatypeSize(layout.label->datatype) == 0) {
      fail(topic, std::string("PointCloud2 field 'label' is ") +
                      datatypeName(layout.label->datatype) +
                      "; publish it as an integer (int8..int32, uint8..uint32) or float32");
    }
    checkFieldFits(msg, *layout.label, topic);
  }
  const auto points = checkedMul(msg.width, msg.height);
  const auto row_bytes = checkedMul(msg.width, msg.point_step);
  if (!points || !row_bytes) {
    fail(topic, "PointCloud2 declares " + std::to_string(msg.width) + " x " +
                    std::to_string(msg.height) + " points of " + std::to_string(msg.point_step) +
                    " bytes, more than memory can hold; fix the publisher's layout");
  }
  layout.points = *points;
  if (layout.points == 0) return layout;
  if (*row_bytes > msg.row_step) {
    fail(topic, "PointCloud2 row_step " + std::to_string(msg.row_step) +
                    " is smaller than width * point_step = " + std::to_string(*row_bytes) +
                    "; fix the publisher's layout");
  }
  const auto needed = checkedMul(msg.row_step, msg.height);
  if (!needed || msg.data.size() < *needed) {
    fail(topic, "PointCloud2 data has " + std::to_string(msg.data.size()) +
                    " bytes, expected row_step * height = " + std::to_string(msg.row_step) +
                    " * " + std::to_string(msg.height) + "; the message is truncated");
  }
  return layout;
}

// The bytes of point `index` (row-major; rows may be padded to row_step). The layout is checked.
const std::uint8_t* pointAt(const sensor_msgs::PointCloud2& msg, std::size_t index) {
  const std::size_t row = index / msg.width, col = index % msg.width;
  return msg.data.data() + row * msg.row_step + col * msg.point_step;
}

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

DecodedClusters decodeClusters(const sensor_msgs::PointCloud2& msg, const std::string& topic) {
  const CloudLayout layout = checkCloudLayout(msg, topic, /*need_label=*/true);
  DecodedClusters out;
  out.points.reserve(layout.points);  // bounded: the data holds every point (checked)
  out.labels.reserve(layout.points);
  for (std::size_t i = 0; i < layout.points; ++i) {
    const std::uint8_t* p = pointAt(msg, i);
    const double x = readScalar(p + layout.axes[0]->offset, layout.axes[0]->datatype);
    const double y = readScalar(p + layout.axes[1]->offset, layout.axes[1]->datatype);
    const double z = readScalar(p + layout.axes[2]->offset, layout.axes[2]->datatype);
    const double l = readScalar(p + layout.label->offset, layout.label->datatype);
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z) || !std::isfinite(l)) {
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

ScanPeople decodeScanPeople(const sensor_msgs::PointCloud2& msg, const std::string& topic) {
  const DecodedClusters decoded = decodeClusters(msg, topic);
  return summariseScan(msg.header.stamp.toSec(), decoded.points, decoded.labels);
}

Frame decodeFrame(const sensor_msgs::Image& image, const sensor_msgs::Image& mask,
                  const sensor_msgs::PointCloud2& clusters, const std::string& image_topic,
                  const std::string& mask_topic, const std::string& clusters_topic) {
  Frame frame;
  frame.stamp_s = image.header.stamp.toSec();
  frame.camera_frame =
      tfFrameId(image.header.frame_id.empty() ? mask.header.frame_id : image.header.frame_id);
  frame.lidar_frame = tfFrameId(clusters.header.frame_id);
  frame.cloud_stamp_s = clusters.header.stamp.toSec();
  frame.image = decodeMonoImage(image, image_topic);
  frame.mask = decodeMonoImage(mask, mask_topic);
  if (frame.image.size() != frame.mask.size()) {
    fail(mask_topic, "mask is " + std::to_string(frame.mask.cols) + "x" +
                         std::to_string(frame.mask.rows) + " but the image on " + image_topic +
                         " is " + std::to_string(frame.image.cols) + "x" +
                         std::to_string(frame.image.rows) +
                         "; segment the same image the camera publishes");
  }
  DecodedClusters decoded = decodeClusters(clusters, clusters_topic);
  frame.points = std::move(decoded.points);
  frame.labels = std::move(decoded.labels);
  frame.nonfinite_points_dropped = decoded.nonfinite_dropped;
  return frame;
}

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
