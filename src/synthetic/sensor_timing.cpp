#include "thermal_lidar_calibration/synthetic/sensor_timing.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace thermal_lidar_calibration {
namespace synthetic {

const char* toString(LidarStamp stamp) {
  switch (stamp) {
    case LidarStamp::kStart: return "start";
    case LidarStamp::kEnd: return "end";
    case LidarStamp::kInstant: break;
  }
  return "instant";
}

LidarStamp lidarStampByName(const std::string& name) {
  if (name == "instant") return LidarStamp::kInstant;
  if (name == "start") return LidarStamp::kStart;
  if (name == "end") return LidarStamp::kEnd;
  throw std::invalid_argument("unknown LiDAR stamp '" + name + "' (use start, end or instant)");
}

void SensorTimingConfig::validate() const {
  if (!(std::abs(camera_time_offset_s) <= 0.5)) {
    throw std::invalid_argument("camera_time_offset_s must be in [-0.5, 0.5] s");
  }
  if (!(lidar_period_s >= 0.01 && lidar_period_s <= 1.0)) {
    throw std::invalid_argument("lidar_period_s must be in [0.01, 1] s");
  }
  if (!std::isfinite(lidar_cut_azimuth_rad)) throw std::invalid_argument("lidar_cut_azimuth_rad must be finite");
  if (lidar_point_time && !swept()) {
    throw std::invalid_argument("per-point LiDAR times need a sweep: give the scan a start or end stamp");
  }
}

// Why one geometry per 5-degree sector is enough: a sector lasts 100 ms / 72 = 1.4 ms at 10 Hz,
// so a point's geometry is taken at most 0.7 ms from its own capture time. In that time the
// fastest drive here (the MS2-like car's field profile, up to 4.8 m/s) moves 3.4 mm, a walker
// (at most 1.5 m/s) 1 mm, and the sharpest turn (about 0.45 rad/s) moves a point 30 m away by
// 1 cm: below the realistic preset's 2 cm range noise, and 0.7 ms is far below the 5 ms a timing
// estimate is asked for. Each point's time field is its own firing's time, not the sector's.
LidarSweep::LidarSweep(const SensorTimingConfig& timing, int azimuth_count)
    : azimuths_(azimuth_count), period_s_(timing.lidar_period_s) {
  if (azimuth_count < 4) throw std::invalid_argument("LidarSweep: need at least 4 azimuths");
  const double turns = timing.lidar_cut_azimuth_rad / (2.0 * M_PI);
  const long long nearest = std::llround((turns - std::floor(turns)) * azimuth_count);
  cut_ = static_cast<int>(nearest % azimuth_count);
  // end: the last firing is at the stamp; start: the first one.
  first_s_ = timing.lidar_stamp == LidarStamp::kEnd ? -period_s_ * (azimuth_count - 1) / azimuth_count : 0.0;
  sector_of_.resize(static_cast<std::size_t>(azimuth_count));
  for (int a = 0; a < azimuth_count; ++a) {
    sector_of_[static_cast<std::size_t>(a)] =
        std::min(kSectors - 1, static_cast<int>(std::floor(fraction(a) * kSectors)));
  }
}

double LidarSweep::fraction(int azimuth) const {
  const int steps = ((cut_ - azimuth) % azimuths_ + azimuths_) % azimuths_;
  return static_cast<double>(steps) / azimuths_;
}

double LidarSweep::timeFromStampAt(double azimuth_rad) const {
  const double cut_rad = 2.0 * M_PI * cut_ / azimuths_;
  double turned = std::fmod(cut_rad - azimuth_rad, 2.0 * M_PI);
  if (turned < 0.0) turned += 2.0 * M_PI;
  return first_s_ + turned / (2.0 * M_PI) * period_s_;
}

double LidarSweep::sectorTimeFromStamp(int sector) const {
  return first_s_ + (sector + 0.5) / kSectors * period_s_;
}

}  // namespace synthetic
}  // namespace thermal_lidar_calibration
