#pragma once
// Which field of a LiDAR cloud holds each point's capture time (parameter point_time_field,
// issue 21). The setting only; the values are decoded where clouds are (ros_io::decodeClusters).

#include <cstdint>
#include <string>
#include <vector>

namespace thermal_lidar_calibration {

struct PointTimeField {
  enum class Mode : std::uint8_t {
    kAuto,   // the first of autoNames() the cloud has; none of them: no per-point times
    kNone,   // ignore any time field
    kNamed,  // exactly `name`: a cloud without it, or with an unusable type, is a bad message
  };
  Mode mode = Mode::kAuto;
  std::string name;

  // "auto", "none" or a field name (letters, digits and '_'). Throws std::invalid_argument.
  static PointTimeField parse(const std::string& value);
  // What auto looks for, in order: velodyne's `time`, ouster's `t`, hesai's `timestamp`,
  // livox's `offset_time`.
  static const std::vector<std::string>& autoNames();
};

}  // namespace thermal_lidar_calibration
