#pragma once
// The boundary between ROS callbacks and the node's code: roscpp lets an exception thrown by a
// subscription or timer callback escape ros::spin(), which ends the node. Every callback of the
// node runs its body through CallbackGuard::run, so a failure is one throttled error naming the
// callback and what went wrong, and the node keeps running.

#include "thermal_lidar_calibration/app/runtime/fault_throttle.hpp"

#include <ros/console.h>

#include <exception>
#include <string>
#include <utility>

namespace thermal_lidar_calibration {
namespace ros_io {

class CallbackGuard {
 public:
  explicit CallbackGuard(double period_s = 5.0) : throttle_(period_s) {}

  // Runs `body()`; returns false (after logging) if it threw.
  template <typename Body>
  bool run(const std::string& callback, Body&& body) {
    try {
      std::forward<Body>(body)();
      return true;
    } catch (const std::exception& e) {
      report(callback, e.what());
    } catch (...) {
      report(callback, "unknown exception");
    }
    return false;
  }

 private:
  void report(const std::string& callback, const std::string& what) {
    if (const auto held_back = throttle_.admit(callback + " failed: " + what)) {
      ROS_ERROR("%s failed: %s; the node keeps running%s", callback.c_str(), what.c_str(),
                throttle_.heldBackText(*held_back).c_str());
    }
  }
  FaultThrottle throttle_;
};

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
