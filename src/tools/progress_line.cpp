#include "thermal_lidar_calibration/tools/progress_line.hpp"

#include <unistd.h>

namespace thermal_lidar_calibration {

ProgressLine::ProgressLine(std::FILE* stream, bool enabled, double period_s)
    : stream_(stream),
      enabled_(enabled),
      tty_(isatty(fileno(stream)) != 0),
      period_s_(period_s),
      last_(std::chrono::steady_clock::now()) {}

void ProgressLine::update(const std::string& text, bool force) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  const double since = std::chrono::duration<double>(now - last_).count();
  if (tty_) {
    if (!force && shown_once_ && since < 0.1) return;
    std::fprintf(stream_, "\r%s\033[K", text.c_str());
    open_line_ = true;
  } else {
    if (!force && since < period_s_) return;
    std::fprintf(stream_, "%s\n", text.c_str());
  }
  std::fflush(stream_);
  shown_once_ = true;
  last_ = now;
}

void ProgressLine::finish() {
  if (!enabled_ || !open_line_) return;
  std::fprintf(stream_, "\n");
  std::fflush(stream_);
  open_line_ = false;
}

}  // namespace thermal_lidar_calibration
