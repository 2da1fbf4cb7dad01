#pragma once
// A live status line on a stream: rewritten in place (\r) on a terminal, else one line every
// `period_s` seconds so logs stay readable.

#include <chrono>
#include <cstdio>
#include <string>

namespace thermal_lidar_calibration {

class ProgressLine {
 public:
  // `enabled` = false makes every call a no-op (--quiet).
  ProgressLine(std::FILE* stream, bool enabled, double period_s = 2.0);
  // Shows `text` now on a terminal (at most ~10 times a second), else if the period has passed
  // (or `force`).
  void update(const std::string& text, bool force = false);
  // Ends the line in place (terminal) so later output starts on a fresh line.
  void finish();

 private:
  std::FILE* stream_;
  bool enabled_;
  bool tty_;
  double period_s_;
  bool open_line_ = false;
  bool shown_once_ = false;
  std::chrono::steady_clock::time_point last_;
};

}  // namespace thermal_lidar_calibration
