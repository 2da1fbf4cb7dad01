#pragma once
// Internal to the ROS adapters: reading sensor_msgs/PointCloud2 fields safely. Every size comes
// from the wire, so a layout is checked (fields inside point_step, data large enough for the
// declared points, no overflow) before any point is read. Failures throw std::invalid_argument
// with one line naming the topic, what was wrong and what to do.

#include "thermal_lidar_calibration/app/parameters/point_time_field.hpp"

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

// The per-point time field `setting` selects in `msg` (checked to fit), or nullptr: none, or
// auto and none of its names present. A named field that is missing, or a chosen field that
// cannot hold times (anything but float32/64 or int32/uint32), fails.
const sensor_msgs::PointField* pointTimeField(const sensor_msgs::PointCloud2& msg, const PointTimeField& setting,
                                              const std::string& topic);

// A point's capture time in seconds from the cloud's header stamp, from its time field. The type
// gives the unit: float32/float64 seconds, int32/uint32 nanoseconds (32 bits of nanoseconds span
// 4.3 s, so they can only be relative: ouster's t, livox's offset_time). Seconds are absolute
// (hesai's timestamp) or relative (velodyne's time): decided once per cloud from its first
// finite time, absolute when it lies nearer the header stamp than zero. (A cloud stamped within
// a sweep of its clock's zero, e.g. the first 0.1 s of a simulation, is read as relative.)
class PointTimeReader {
 public:
  PointTimeReader(const sensor_msgs::PointField& field, double stamp_s);
  // NaN when the stored time is not finite.
  double secondsFromStamp(const std::uint8_t* point);

 private:
  std::uint32_t offset_;
  std::uint8_t datatype_;
  bool nanoseconds_;
  double stamp_s_;
  int absolute_ = -1;  // -1 until the first finite time decides
};

}  // namespace cloud_fields
}  // namespace ros_io
}  // namespace thermal_lidar_calibration
