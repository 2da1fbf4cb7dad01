// Reading PointCloud2 fields safely: see cloud_fields.hpp.

#include "cloud_fields.hpp"

#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

namespace thermal_lidar_calibration {
namespace ros_io {
namespace cloud_fields {

void fail(const std::string& topic, const std::string& what) {
  throw std::invalid_argument((topic.empty() ? std::string() : topic + ": ") + what);
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

const sensor_msgs::PointField* pointTimeField(const sensor_msgs::PointCloud2& msg, const PointTimeField& setting,
                                              const std::string& topic) {
  const sensor_msgs::PointField* field = nullptr;
  switch (setting.mode) {
    case PointTimeField::Mode::kNone: return nullptr;
    case PointTimeField::Mode::kAuto:
      for (const std::string& name : PointTimeField::autoNames()) {
        if ((field = findField(msg, name))) break;
      }
      if (!field) return nullptr;
      break;
    case PointTimeField::Mode::kNamed:
      field = findField(msg, setting.name);
      if (!field) {
        fail(topic, "PointCloud2 has no point time field '" + setting.name + "' (fields: " + fieldList(msg) +
                        "); set point_time_field to one of them, auto or none");
      }
      break;
  }
  const std::uint8_t t = field->datatype;
  if (t != sensor_msgs::PointField::FLOAT32 && t != sensor_msgs::PointField::FLOAT64 &&
      t != sensor_msgs::PointField::INT32 && t != sensor_msgs::PointField::UINT32) {
    fail(topic, "PointCloud2 point time field '" + field->name + "' is " + datatypeName(t) +
                    "; times must be float32/float64 seconds or int32/uint32 nanoseconds "
                    "(point_time_field: none ignores them)");
  }
  checkFieldFits(msg, *field, topic);
  return field;
}

PointTimeReader::PointTimeReader(const sensor_msgs::PointField& field, double stamp_s)
    : offset_(field.offset),
      datatype_(field.datatype),
      nanoseconds_(field.datatype == sensor_msgs::PointField::INT32 ||
                   field.datatype == sensor_msgs::PointField::UINT32),
      stamp_s_(stamp_s) {}

double PointTimeReader::secondsFromStamp(const std::uint8_t* point) {
  const double raw = readScalar(point + offset_, datatype_);
  if (nanoseconds_) return raw * 1e-9;
  if (!std::isfinite(raw)) return std::numeric_limits<double>::quiet_NaN();
  if (absolute_ < 0) absolute_ = std::abs(raw - stamp_s_) < std::abs(raw) ? 1 : 0;
  return absolute_ ? raw - stamp_s_ : raw;
}

}  // namespace cloud_fields
}  // namespace ros_io
}  // namespace thermal_lidar_calibration
