#include "thermal_lidar_calibration/synthetic/drive_schedule.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

namespace thermal_lidar_calibration {
namespace synthetic {
namespace {

constexpr double kStopProbability = 0.2;
constexpr double kMinSpeedChange = 0.3;  // x cruise: a new speed differs from the last by this at least

}  // namespace

const char* toString(SpeedProfile profile) {
  return profile == SpeedProfile::kField ? "field" : "steady";
}

SpeedProfile speedProfileByName(const std::string& name) {
  if (name == "steady") return SpeedProfile::kSteady;
  if (name == "field") return SpeedProfile::kField;
  throw std::invalid_argument("unknown speed profile '" + name + "' (use steady or field)");
}

DriveSchedule DriveSchedule::steady(double speed_mps) {
  if (!(speed_mps > 0.0)) throw std::invalid_argument("steady drive: speed must be > 0");
  DriveSchedule d;
  d.steady_mps_ = speed_mps;
  d.max_speed_mps_ = speed_mps;
  return d;
}

DriveSchedule DriveSchedule::field(double cruise_mps, double duration_s, std::uint64_t seed) {
  if (!(cruise_mps > 0.0) || !(duration_s > 0.0)) {
    throw std::invalid_argument("field drive: cruise speed and duration must be > 0");
  }
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  auto uniform = [&](double a, double b) { return a + (b - a) * unit(rng); };
  const double max_accel = 0.2 * cruise_mps;
  auto cruise = [&]() { return cruise_mps * uniform(0.4, 1.2); };

  DriveSchedule d;
  double t = 0.0, s = 0.0, v = cruise();
  // Past the drive's end by a margin: the camera's offset and the LiDAR's sweep look up to
  // 0.6 s beyond the last stamp.
  while (t < duration_s + 2.0) {
    const bool stopped = v == 0.0;
    const double hold = stopped ? uniform(1.5, 4.0) : uniform(2.0, 6.0);
    d.segments_.push_back({t, hold, v, v, s});
    t += hold;
    s += v * hold;
    double next = 0.0;
    if (stopped || unit(rng) >= kStopProbability) {
      do {
        next = cruise();
      } while (std::abs(next - v) < kMinSpeedChange * cruise_mps);
    }
    // Peak acceleration of a half-cosine ramp: pi / 2 * |dv| / D.
    const double ramp = std::max(1.0, M_PI * std::abs(next - v) / (2.0 * max_accel));
    d.segments_.push_back({t, ramp, v, next, s});
    s += 0.5 * (v + next) * ramp;
    t += ramp;
    v = next;
  }
  for (const Segment& seg : d.segments_) d.max_speed_mps_ = std::max({d.max_speed_mps_, seg.v0, seg.v1});
  return d;
}

const DriveSchedule::Segment& DriveSchedule::segmentAt(double t_s) const {
  const auto after = std::upper_bound(segments_.begin(), segments_.end(), t_s,
                                      [](double t, const Segment& seg) { return t < seg.t0; });
  return after == segments_.begin() ? segments_.front() : *(after - 1);
}

double DriveSchedule::distanceInto(const Segment& seg, double tau) {
  if (tau <= 0.0) return seg.v0 * tau;
  if (tau >= seg.duration) {
    return distanceInto(seg, seg.duration) + seg.v1 * (tau - seg.duration);
  }
  // v(tau) = v0 + (v1 - v0) (1 - cos(pi tau / D)) / 2, integrated from 0.
  const double w = M_PI / seg.duration;
  return seg.v0 * tau + 0.5 * (seg.v1 - seg.v0) * (tau - std::sin(w * tau) / w);
}

double DriveSchedule::speedInto(const Segment& seg, double tau) {
  if (tau <= 0.0) return seg.v0;
  if (tau >= seg.duration) return seg.v1;
  return seg.v0 + 0.5 * (seg.v1 - seg.v0) * (1.0 - std::cos(M_PI * tau / seg.duration));
}

double DriveSchedule::arcLengthAt(double t_s) const {
  if (steady_mps_ >= 0.0) return steady_mps_ * t_s;
  const Segment& seg = segmentAt(t_s);
  return seg.s0 + distanceInto(seg, t_s - seg.t0);
}

double DriveSchedule::speedAt(double t_s) const {
  if (steady_mps_ >= 0.0) return steady_mps_;
  const Segment& seg = segmentAt(t_s);
  return speedInto(seg, t_s - seg.t0);
}

}  // namespace synthetic
}  // namespace thermal_lidar_calibration
