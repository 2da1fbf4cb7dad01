// StampGuard: keeps ApproximateTime's stamp arithmetic in range.

#include "thermal_lidar_calibration/ros/stamp_guard.hpp"

#include <cinttypes>
#include <cstdio>
#include <limits>

namespace thermal_lidar_calibration {
namespace ros_io {
namespace {

constexpr std::uint32_t kNsecPerSec = 1000000000u;

// |a - b| in seconds without ros::Duration (which throws beyond 2^31 s).
double distanceS(const ros::Time& a, const ros::Time& b) {
  const double d = (static_cast<double>(a.sec) - static_cast<double>(b.sec)) +
                   1e-9 * (static_cast<double>(a.nsec) - static_cast<double>(b.nsec));
  return d < 0 ? -d : d;
}

}  // namespace

std::string stampString(const ros::Time& stamp) {
  char text[32];
  std::snprintf(text, sizeof(text), "%" PRIu32 ".%09" PRIu32, stamp.sec, stamp.nsec);
  return text;
}

StampGuard::Decision StampGuard::check(const ros::Time& stamp) {
  if (stamp.isZero()) {
    return {Verdict::kRefuse, "stamp 0 (the stamp of a sensor whose clock is not set)"};
  }
  if (stamp.nsec >= kNsecPerSec) {
    return {Verdict::kRefuse, "stamp " + std::to_string(stamp.sec) + " s + " +
                                  std::to_string(stamp.nsec) +
                                  " ns is not normalised (nsec >= 1e9): a corrupt header"};
  }
  // ApproximateTime adds durations up to the slop to stamps: keep clear of the uint32 end.
  if (static_cast<double>(stamp.sec) >
      static_cast<double>(std::numeric_limits<std::uint32_t>::max()) - kMaxJumpS) {
    return {Verdict::kRefuse, "stamp " + stampString(stamp) +
                                  " is at the end of ROS time (an unset or corrupt clock)"};
  }
  if (!base_ || distanceS(stamp, *base_) <= kMaxJumpS) {
    base_ = stamp;
    candidate_.reset();
    candidate_count_ = 0;
    return {};
  }
  if (candidate_ && distanceS(stamp, *candidate_) <= kMaxJumpS) {
    ++candidate_count_;
  } else {
    candidate_ = stamp;
    candidate_count_ = 1;
  }
  if (candidate_count_ >= kMessagesToMove) {
    const std::string reason = "the data's time moved from " + stampString(*base_) + " to " +
                               stampString(stamp) + " (" + std::to_string(candidate_count_) +
                               " messages agree); pairing restarts from there";
    base_ = stamp;
    candidate_.reset();
    candidate_count_ = 0;
    return {Verdict::kMoveTimeBase, reason};
  }
  return {Verdict::kRefuse, "stamp " + stampString(stamp) + " is more than " +
                                std::to_string(static_cast<int>(kMaxJumpS)) +
                                " s from the data's time " + stampString(*base_) +
                                " (a sensor clock unset or wrong?); message dropped"};
}

void StampGuard::reset() {
  base_.reset();
  candidate_.reset();
  candidate_count_ = 0;
}

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
