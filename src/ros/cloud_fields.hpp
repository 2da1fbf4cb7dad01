#pragma once
// Internal to the ROS adapters: reading sensor_msgs/PointCloud2 fields safely. Every size comes
// from the wire, so a layout is checked (fields inside point_step, data large enough for the
// declared points, no overflow) before any point is read. Failures throw std::invalid_argument
// with one line naming the topic, what was wrong and what to do.

#include <sensor_msgs/PointCloud2.h>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

namespace thermal_lidar_calibration {
namespace ros_io {
namespace cloud_fields {

[[noreturn]] void fail(const std::string& topic, const std::string& what);

// a * b, or nullopt when it does not fit in size_t: declared sizes come from the wire.
inline std::optional<std::size_t> checkedMul(std::size_t a, std::size_t b) {
  std::size_t out = 0;
  if (__builtin_mul_overflow(a, b, &out)) return std::nullopt;
  return out;
}

const char* datatypeName(std::uint8_t datatype);
std::size_t datatypeSize(std::uint8_t datatype);  // 0 for an unknown datatype
// Reads one scalar of `datatype` at `p` (little-endian host assumed, as checked by the caller).
double readScalar(const std::uint8_t* p, std::uint8_t datatype);
std::string fieldList(const sensor_msgs::PointCloud2& msg);
const sensor_msgs::PointField* findField(const sensor_msgs::PointCloud2& msg, const std::string& name);
// A known datatype whose value lies inside point_step, or a failure naming the field.
void checkFieldFits(const sensor_msgs::PointCloud2& msg, const sensor_msgs::PointField& f,
                    const std::string& topic);

// A PointCloud2 whose layout was checked: x, y, z (float32 or float64) and, when asked for,
// `label`, every field inside point_step, and row_step and data large enough for
// width x height points, every size computed without overflow. The one check every cloud
// decoder (clusters of the ingest path, ~overlay_cloud, raw scans) goes through.
struct CloudLayout {
  const sensor_msgs::PointField* axes[3] = {nullptr, nullptr, nullptr};
  const sensor_msgs::PointField* label = nullptr;
  std::size_t points = 0;  // width * height
};
CloudLayout checkCloudLayout(const sensor_msgs::PointCloud2& msg, const std::string& topic, bool need_label);

// The bytes of point `index` (row-major; rows may be padded to row_step). The layout is checked.
inline const std::uint8_t* pointAt(const sensor_msgs::PointCloud2& msg, std::size_t index) {
  const std::size_t row = index / msg.width, col = index % msg.width;
  return msg.data.data() + row * msg.row_step + col * msg.point_step;
}

}  // namespace cloud_fields
}  // namespace ros_io
}  // namespace thermal_lidar_calibration
