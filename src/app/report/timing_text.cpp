#include "thermal_lidar_calibration/app/report/timing_text.hpp"

#include <cmath>
#include <cstdio>

namespace thermal_lidar_calibration {

std::string timeOffsetText(const CalibrationResult& result, const std::optional<Uncertainty>& uncertainty) {
  if (result.time_offset_mode == TimeOffsetMode::kNone) {
    return result.time_offset_note.empty() ? "not used (time_offset_mode none)" : result.time_offset_note;
  }
  char text[128];
  if (result.time_offset_mode == TimeOffsetMode::kFixed) {
    if (result.time_offset_asked == TimeOffsetMode::kEstimate) {  // the pairs could not resolve it
      std::snprintf(text, sizeof(text), "%+.1f ms, ", 1000.0 * result.time_offset_s);
      return text + result.time_offset_note;
    }
    std::snprintf(text, sizeof(text), "%+.1f ms (fixed)", 1000.0 * result.time_offset_s);
  } else if (uncertainty && uncertainty->timed && uncertainty->resamples >= 2) {
    std::snprintf(text, sizeof(text), "%+.1f ms (estimated, +-%.1f ms)", 1000.0 * result.time_offset_s,
                  uncertainty->time_offset_ms);
  } else {
    std::snprintf(text, sizeof(text), "%+.1f ms (estimated)", 1000.0 * result.time_offset_s);
  }
  return text;
}

std::string timeOffsetWarning(const CalibrationResult& result) {
  if (result.time_offset_mode == TimeOffsetMode::kNone || std::abs(result.time_offset_s) <= kTimeOffsetWarnS) {
    return "";
  }
  const double ms = 1000.0 * result.time_offset_s;
  char text[400];
  std::snprintf(text, sizeof(text),
                "the thermal images were captured %.0f ms %s their stamps (LiDAR clock): set the camera "
                "driver's time offset to %+.0f ms, or keep time_offset_s: %.4f with time_offset_mode: fixed",
                std::abs(ms), ms > 0 ? "after" : "before", ms, result.time_offset_s);
  return text;
}

}  // namespace thermal_lidar_calibration
