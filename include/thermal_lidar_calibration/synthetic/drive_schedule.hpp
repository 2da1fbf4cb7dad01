#pragma once
// How far along its path the vehicle has driven at each instant of a synthetic drive (issue 21):
// the speed is continuous (no jumps, so positions and velocities are too) and the arc length is
// its exact integral.

#include <cstdint>
#include <string>
#include <vector>

namespace thermal_lidar_calibration {
namespace synthetic {

// steady: one speed all the way (the drive before issue 21, unchanged). field: a tractor at work:
// it stops, speeds up and slows down (0 to 1.2 x the rig's speed: 0-3 m/s on the FieldSAFE-like
// rig, 0-4.8 m/s on the MS2-like car), and its path meanders (Scene).
enum class SpeedProfile : std::uint8_t { kSteady, kField };
const char* toString(SpeedProfile profile);
// "steady" or "field"; anything else throws std::invalid_argument.
SpeedProfile speedProfileByName(const std::string& name);

class DriveSchedule {
 public:
  // Arc length speed_mps * t, at every t (the steady drive).
  static DriveSchedule steady(double speed_mps);
  // Holds of 2-6 s at 0.4-1.2 x cruise_mps, one in five a stop of 1.5-4 s instead, joined by
  // half-cosine ramps whose peak acceleration is at most 0.2 x cruise_mps per second (0.5 m/s^2
  // for a tractor at 2.5 m/s), until at least `duration_s`. Drawn from `seed` alone.
  static DriveSchedule field(double cruise_mps, double duration_s, std::uint64_t seed);

  // Before 0 s the first speed holds (the vehicle was already driving); after the last segment
  // the last speed holds.
  double arcLengthAt(double t_s) const;
  double speedAt(double t_s) const;
  double maxSpeed() const { return max_speed_mps_; }

 private:
  // From t0 for `duration` seconds the speed goes from v0 to v1 along a half cosine (v0 == v1:
  // a hold); s0 is the arc length at t0.
  struct Segment {
    double t0 = 0, duration = 0, v0 = 0, v1 = 0, s0 = 0;
  };
  const Segment& segmentAt(double t_s) const;
  static double distanceInto(const Segment& seg, double tau);
  static double speedInto(const Segment& seg, double tau);

  std::vector<Segment> segments_;
  double steady_mps_ = -1.0;  // >= 0: the steady schedule (arc length = speed * t, exactly)
  double max_speed_mps_ = 0.0;
};

}  // namespace synthetic
}  // namespace thermal_lidar_calibration
