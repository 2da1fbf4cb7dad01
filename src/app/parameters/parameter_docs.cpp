// config/default.yaml and README's parameter table, rendered from the parameter rows.

#include "thermal_lidar_calibration/app/parameters/parameter_docs.hpp"

#include <cctype>
#include <stdexcept>

namespace thermal_lidar_calibration {
namespace {

constexpr std::size_t kYamlCommentColumn = 35;  // "key: value" padded to here, then "# ..."
constexpr std::size_t kYamlRuleWidth = 94;       // width of the "# --- Section ---" lines

const char* const kYamlHeader =
    "# thermal_lidar_calibration: every parameter, with its default (the paper's Table 1, SI units).\n"
    "# Flat keys. calibration_node reads them as private parameters (~key, e.g. rosparam load this\n"
    "# file into the node's namespace); calibrate_bag reads the same file with --config.\n"
    "# Units: metres, radians, seconds, pixels. Ranges are checked at start: a bad value stops the\n"
    "# node / tool with \"parameter 'key' = value: must be ...\".\n"
    "# Generated from the parameter tables (src/app/parameters/core_parameter_table.cpp,\n"
    "# src/app/parameters/node_parameter_table.cpp) by scripts/update_parameter_docs.sh: edit a row there,\n"
    "# not this file (test_parameter_docs fails while they disagree).\n";

std::pair<std::size_t, std::size_t> blockBounds(const std::string& text, const std::string& begin,
                                                const std::string& end) {
  const std::size_t b = text.find(begin + "\n");
  if (b == std::string::npos) throw std::invalid_argument("marker line not found: " + begin);
  const std::size_t body = b + begin.size() + 1;
  const std::size_t e = text.find(end + "\n", body);
  if (e == std::string::npos || (e > 0 && text[e - 1] != '\n')) {
    throw std::invalid_argument("marker line not found after " + begin + ": " + end);
  }
  return {body, e};
}

// "<camera_frame>" would be read as an HTML tag and vanish from the rendered page.
std::string markdownText(const std::string& text) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const bool tag = text[i] == '<' && i + 1 < text.size() && std::isalpha(static_cast<unsigned char>(text[i + 1]));
    out += tag ? "\\<" : std::string(1, text[i]);
  }
  return out;
}

}  // namespace

const char* const kParameterTableBegin =
    "<!-- parameter table: generated from the parameter tables by "
    "scripts/update_parameter_docs.sh -->";
const char* const kParameterTableEnd = "<!-- end of the parameter table -->";

std::string renderDefaultYaml(const std::vector<ParameterDoc>& docs) {
  std::string out = kYamlHeader;
  std::string section;
  for (const auto& doc : docs) {
    if (doc.section != section || &doc == &docs.front()) {
      section = doc.section;
      std::string rule = "# --- " + section + " ";
      if (rule.size() < kYamlRuleWidth) rule.append(kYamlRuleWidth - rule.size(), '-');
      out += "\n" + rule + "\n";
    }
    std::string line = doc.key + ": " + doc.default_yaml;
    line.append(line.size() + 2 <= kYamlCommentColumn ? kYamlCommentColumn - line.size() : 2, ' ');
    out += line + "# " + doc.meaning + "\n";
  }
  return out;
}

std::string renderParameterMarkdown(const std::vector<ParameterDoc>& docs) {
  std::string out =
      "| parameter | default | meaning, unit; allowed values |\n"
      "|---|---|---|\n";
  std::string section;
  for (const auto& doc : docs) {
    if (doc.section != section || &doc == &docs.front()) {
      section = doc.section;
      out += "| **" + section + "** | | |\n";
    }
    out += "| `" + doc.key + "` | `" + doc.default_yaml + "` | " + markdownText(doc.meaning) + " |\n";
  }
  return out;
}

std::string replaceMarkedBlock(const std::string& text, const std::string& begin,
                               const std::string& end, const std::string& body) {
  const auto [from, to] = blockBounds(text, begin, end);
  return text.substr(0, from) + body + text.substr(to);
}

std::string markedBlock(const std::string& text, const std::string& begin, const std::string& end) {
  const auto [from, to] = blockBounds(text, begin, end);
  return text.substr(from, to - from);
}

}  // namespace thermal_lidar_calibration
