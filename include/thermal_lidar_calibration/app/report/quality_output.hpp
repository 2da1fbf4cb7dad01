#pragma once
// The quality assessment (uncertainty, coverage, verdict, reference) as the result file's keys
// (docs/INTERFACE.md, "Quality") and as the lines of the calibration summary.

#include "thermal_lidar_calibration/core/quality_assessment.hpp"

#include <yaml-cpp/yaml.h>

#include <string>

namespace thermal_lidar_calibration {

// The `uncertainty:` block (half-widths per axis and how they were made), into an open map.
void emitUncertainty(YAML::Emitter& out, const Uncertainty& uncertainty);

// "+-[0.100, 0.050, 0.200] deg, +-[1.50, 4.00, 2.00] cm": the half-widths about camera x, y, z.
std::string formatHalfWidths(const Uncertainty& uncertainty);

// uncertainty, coverage, verdict, verdict_reasons and (when known) reference, into the map the
// caller has opened.
void emitQuality(YAML::Emitter& out, const QualityAssessment& quality);

// "  uncertainty  +- ..." lines for the summary, each ending in '\n'.
std::string formatQualitySummary(const QualityAssessment& quality);

}  // namespace thermal_lidar_calibration
