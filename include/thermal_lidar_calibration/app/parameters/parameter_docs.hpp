#pragma once
// The parameter documentation rendered from the tables' rows: config/default.yaml (every key
// with its default and a comment) and README's parameter table. test_parameter_docs compares
// the committed files with these; scripts/update_parameter_docs.sh rewrites them.

#include "thermal_lidar_calibration/app/parameters/parameter_table.hpp"

#include <string>
#include <vector>

namespace thermal_lidar_calibration {

// README's table sits between these two lines.
extern const char* const kParameterTableBegin;
extern const char* const kParameterTableEnd;

std::string renderDefaultYaml(const std::vector<ParameterDoc>& docs);
std::string renderParameterMarkdown(const std::vector<ParameterDoc>& docs);

// `text` with the lines strictly between the `begin` and `end` lines replaced by `body`.
// Throws std::invalid_argument when a marker is missing.
std::string replaceMarkedBlock(const std::string& text, const std::string& begin,
                               const std::string& end, const std::string& body);
// The lines strictly between the markers (throws the same way).
std::string markedBlock(const std::string& text, const std::string& begin, const std::string& end);

}  // namespace thermal_lidar_calibration
