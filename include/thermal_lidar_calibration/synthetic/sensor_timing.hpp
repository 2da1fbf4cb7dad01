#pragma once
// When each sensor of the synthetic rig sees the world (issue 21): the thermal camera's offset
// from its stamps, and the LiDAR's sweep over one rotation. ROS-free.
//
// Conventions (INTERFACE.md, "Sensor timing"): the image stamped t shows the world at
// t + camera_time_offset_s (the time_offset_s, delta, a calibration should find). A swept scan
// is stamped at its first point (start, as Ouster's driver stamps) or at its last (end, as the
// velodyne driver stamps with its last packet); each point is captured when the head turns past
// its azimuth and is expressed in the LiDAR frame of that instant (not motion-compensated).

#include <cstdint>
#include <string>
#include <vector>

namespace thermal_lidar_calibration {
namespace synthetic {

enum class LidarStamp : std::uint8_t { kInstant, kStart, kEnd };
const char* toString(LidarStamp stamp);  // "instant", "start", "end"
// "instant", "start" or "end"; anything else throws std::invalid_argument.
LidarStamp lidarStampByName(const std::string& name);

struct SensorTimingConfig {
  double camera_time_offset_s = 0.0;  // |.| <= 0.5 s
  LidarStamp lidar_stamp = LidarStamp::kInstant;  // kInstant: the whole scan at its stamp
  bool lidar_point_time = false;      // swept points carry their time (needs a sweep)
  double lidar_period_s = 0.1;        // one rotation (10 Hz)
  // Where a sweep starts and ends, radians counter-clockwise from the LiDAR's +x (forward). Pi:
  // behind the vehicle, so the camera's forward view is swept mid-rotation, 50 ms from either
  // stamp at 10 Hz. (velodyne_driver's own default differs: ROS 1 cuts by packet count, so the
  // cut wanders; ROS 2 cuts at the sensor's azimuth 0, straight ahead; Ouster starts behind.)
  double lidar_cut_azimuth_rad = 3.14159265358979323846;
  bool swept() const { return lidar_stamp != LidarStamp::kInstant; }
  void validate() const;  // throws std::invalid_argument
};

// One rotation of a spinning LiDAR with `azimuth_count` firings, turning clockwise seen from
// above (as Velodyne and Ouster heads do: azimuth index decreasing in the LidarModel's
// counter-clockwise convention), starting at the cut. Everything in seconds relative to the
// scan's stamp.
class LidarSweep {
 public:
  // Sector size: geometry is taken once per sector, at its middle instant; see the .cpp for why
  // 5 degrees is fine.
  static constexpr int kSectors = 72;

  LidarSweep(const SensorTimingConfig& timing, int azimuth_count);

  // Capture time of the firing at `azimuth` (index into the LidarModel's azimuths).
  double timeFromStamp(int azimuth) const { return first_s_ + fraction(azimuth) * period_s_; }
  // Capture time of the direction `azimuth_rad` (e.g. the camera's optical axis).
  double timeFromStampAt(double azimuth_rad) const;
  int sectorOf(int azimuth) const { return sector_of_[static_cast<std::size_t>(azimuth)]; }
  const std::vector<int>& sectorOfAzimuth() const { return sector_of_; }  // one per azimuth index
  // The instant sector `sector`'s geometry is taken (its middle).
  double sectorTimeFromStamp(int sector) const;
  double firstPointFromStamp() const { return first_s_; }
  double lastPointFromStamp() const { return first_s_ + fraction(cut_ + 1) * period_s_; }
  int azimuthCount() const { return azimuths_; }

 private:
  double fraction(int azimuth) const;  // 0 for the first firing, (n-1)/n for the last

  int azimuths_ = 0;
  int cut_ = 0;            // azimuth index of the first firing
  double period_s_ = 0.1;
  double first_s_ = 0.0;   // time of the first firing from the stamp
  std::vector<int> sector_of_;
};

}  // namespace synthetic
}  // namespace thermal_lidar_calibration
