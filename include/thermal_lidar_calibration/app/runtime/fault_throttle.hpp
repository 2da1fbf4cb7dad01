#pragma once
// Throttling of per-message fault warnings by KIND of fault: at most one line per kind and
// period, and that line counts what it held back ("... and 212 more like it"). A fault's kind is
// its text with every number taken out, because sizes, stamps and ids make each bad frame's text
// different (keyed on the full text, 474 bad frames gave 389 lines). ROS_WARN_THROTTLE would
// throttle per call site and hide a second kind of fault behind the first.

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <unordered_map>

namespace thermal_lidar_calibration {

class FaultThrottle {
 public:
  using Clock = std::chrono::steady_clock;

  explicit FaultThrottle(double period_s) : period_(period_s) {}
  double periodS() const { return period_.count(); }

  // `fault` with every run of digits (and a number's sign, point and exponent) replaced by '#':
  // "mask 640x480 at 12.5" and "mask 320x240 at 13.0" are one kind.
  static std::string kindOf(const std::string& fault);

  // std::nullopt: stay silent (the fault is counted for its kind's next line). Otherwise report
  // now; the value is how many faults of this kind were held back since its previous line.
  std::optional<std::uint64_t> admit(const std::string& fault, Clock::time_point now = Clock::now());

  // " (and 212 more like it in the last 5 s)", or "" for 0.
  std::string heldBackText(std::uint64_t held_back) const;

 private:
  struct Kind {
    Clock::time_point last_report;
    std::uint64_t held_back = 0;
  };
  std::chrono::duration<double> period_;
  std::unordered_map<std::string, Kind> kinds_;
};

}  // namespace thermal_lidar_calibration
