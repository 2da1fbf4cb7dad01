#pragma once
// Which header stamps may enter message_filters' ApproximateTime. It subtracts stamps as
// ros::Duration (int32 seconds) and adds durations to ros::Time (uint32 seconds), both of which
// throw when out of range: an image stamped 1600000000 beside a mask stamped 4294967295 (or 0
// beside 2.2e9) ends the caller with "Duration is out of dual 32-bit range". A sensor with an
// unset clock is ordinary in the field, so such a message is refused with a reason instead.
//
// Stamp 0 (a clock not set), a stamp at the end of ROS time and one with nsec >= 1e9 are refused
// outright. Otherwise a stamp is accepted when it lies within kMaxJumpS of the latest accepted
// stamp (the data's time). Accepted stamps then never spread by more than kMaxJumpS per message
// held, far below the 68 years at which the arithmetic overflows. A single stray message cannot fix the
// time base: when kMessagesToMove consecutive refused messages agree with each other (the
// data really moved to another epoch, e.g. a second bag or a clock set late), the base moves to
// them and the caller restarts the synchronizer.

#include <ros/time.h>

#include <cstdint>
#include <optional>
#include <string>

namespace thermal_lidar_calibration {
namespace ros_io {

class StampGuard {
 public:
  static constexpr double kMaxJumpS = 3600.0;
  static constexpr int kMessagesToMove = 10;

  enum class Verdict { kAccept, kRefuse, kMoveTimeBase };
  struct Decision {
    Verdict verdict = Verdict::kAccept;
    std::string reason;  // kRefuse / kMoveTimeBase: one line, names the stamp
  };

  Decision check(const ros::Time& stamp);
  // The latest accepted stamp (the data's own time), if any.
  std::optional<ros::Time> dataTime() const { return base_; }
  void reset();

 private:
  std::optional<ros::Time> base_;
  std::optional<ros::Time> candidate_;  // first of the current run of refused, agreeing stamps
  int candidate_count_ = 0;
};

// "1600000000.123456789" (exact; toSec() would round at epoch times).
std::string stampString(const ros::Time& stamp);

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
