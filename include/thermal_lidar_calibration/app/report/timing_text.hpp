#pragma once
// The camera's time offset in words, one wording for calibrate_bag's summary, the node's log,
// ~status and /diagnostics (issue 21).

#include "thermal_lidar_calibration/core/calibrator.hpp"
#include "thermal_lidar_calibration/core/uncertainty.hpp"

#include <optional>
#include <string>

namespace thermal_lidar_calibration {

// Above this a user is told the stamps are off and what to change.
constexpr double kTimeOffsetWarnS = 0.02;

// "+59.7 ms (estimated, +-3.1 ms)", "+60.0 ms (fixed)", "not applied: <why>", "not used (none)".
std::string timeOffsetText(const CalibrationResult& result, const std::optional<Uncertainty>& uncertainty);

// One line when |delta| > kTimeOffsetWarnS: what the stamps are off by and what to change; ""
// otherwise.
std::string timeOffsetWarning(const CalibrationResult& result);

}  // namespace thermal_lidar_calibration
