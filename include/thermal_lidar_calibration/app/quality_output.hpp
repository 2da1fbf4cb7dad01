#pragma once
// The quality assessment (uncertainty, coverage, verdict, reference) as the result file's keys
// (docs/INTERFACE.md, "Quality") and as the lines of the calibration summary.

#include "thermal_lidar_calibration/core/quality_assessment.hpp"

#include <yaml-cpp/yaml.h>

#include <string>

namespace thermal_lidar_calibration {

// uncertainty, coverage, verdict, verdict_reasons and (when known) reference, into the map the
// caller has opened.
void emitQuality(YAML::Emitter& out, const QualityAssessment& quality);

// "  uncertainty  +- ..." lines for the summary, each ending in '\n'.
std::string formatQualitySummary(const QualityAssessment& quality);

}  // namespace thermal_lidar_calibration
