// The per-type halves of the parameter rows: reading with range checks, the one error wording,
// and the text of values and allowed ranges for logs and documentation.

#include "thermal_lidar_calibration/app/parameters/parameter_table.hpp"

#include <cctype>
#include <cmath>
#include <limits>
#include <sstream>

namespace thermal_lidar_calibration {

std::string formatParameterNumber(double v) {
  std::ostringstream s;
  s.precision(12);
  s << v;
  return s.str();
}

std::string parameterValueText(const ParameterSource& source, const std::string& key) {
  if (auto i = source.getInt(key)) return std::to_string(*i);
  if (auto d = source.getDouble(key)) return formatParameterNumber(*d);
  if (auto b = source.getBool(key)) return *b ? "true" : "false";
  if (auto s = source.getString(key)) return "'" + *s + "'";
  return "<not a scalar>";
}

void throwBadParameter(const ParameterSource& source, const std::string& key,
                       const std::string& requirement) {
  throw std::invalid_argument("parameter '" + key + "' = " + parameterValueText(source, key) +
                              ": " + requirement);
}

namespace parameter_detail {

std::optional<long long> readInt(const ParameterSource& s, const std::string& key, IntRange r) {
  if (!s.has(key)) return std::nullopt;
  const auto v = s.getInt(key);
  if (!v || *v < r.lo || *v > r.hi) {
    throwBadParameter(s, key,
                      "must be an integer in [" + std::to_string(r.lo) + ", " + std::to_string(r.hi) + "]");
  }
  return v;
}

std::optional<double> readReal(const ParameterSource& s, const std::string& key, RealRange r) {
  if (!s.has(key)) return std::nullopt;
  const auto v = s.getDouble(key);
  if (!v || !std::isfinite(*v) || *v > r.hi || (r.lo_open ? *v <= r.lo : *v < r.lo)) {
    throwBadParameter(s, key, "must be a number in " + allowedReal(r));
  }
  return v;
}

std::optional<bool> readBool(const ParameterSource& s, const std::string& key) {
  if (!s.has(key)) return std::nullopt;
  const auto v = s.getBool(key);
  if (!v) throwBadParameter(s, key, "must be true or false");
  return v;
}

std::optional<std::string> readText(const ParameterSource& s, const std::string& key,
                                    const TextRule& rule) {
  if (!s.has(key)) return std::nullopt;
  const auto v = s.getString(key);
  if (!v) throwBadParameter(s, key, "must be a string");
  if (v->empty() && !rule.requirement.empty()) throwBadParameter(s, key, rule.requirement);
  return v;
}

std::optional<std::size_t> readChoice(const ParameterSource& s, const std::string& key,
                                      const std::vector<std::string>& names, bool as_integer,
                                      const std::string& requirement) {
  if (!s.has(key)) return std::nullopt;
  std::optional<std::string> name;
  if (as_integer) {
    if (const auto i = s.getInt(key)) name = std::to_string(*i);
  } else {
    name = s.getString(key);
  }
  for (std::size_t i = 0; name && i < names.size(); ++i) {
    if (names[i] == *name) return i;
  }
  throwBadParameter(s, key, requirement);
}

std::string allowedInt(IntRange r) {
  if (r.hi == std::numeric_limits<long long>::max()) return "integer >= " + std::to_string(r.lo);
  return "integer [" + std::to_string(r.lo) + ", " + std::to_string(r.hi) + "]";
}

std::string allowedReal(RealRange r) {
  return std::string(r.lo_open ? "(" : "[") + formatParameterNumber(r.lo) + ", " +
         formatParameterNumber(r.hi) + "]";
}

std::string allowedText(const TextRule& rule) {
  if (!rule.requirement.empty()) return "non-empty";
  if (!rule.empty_means.empty()) return "\"\" = " + rule.empty_means;
  return "string";
}

std::string allowedChoice(const std::vector<std::string>& names) {
  std::string out = "{";
  for (std::size_t i = 0; i < names.size(); ++i) out += (i ? ", " : "") + names[i];
  return out + "}";
}

std::string describeText(const std::string& value, const TextRule& rule) {
  if (!value.empty()) return value;
  return rule.empty_means.empty() ? "''" : "'' (" + rule.empty_means + ")";
}

// PyYAML (rosparam) reads a number as a float only with a '.' and a signed exponent
// ("1.0e-06", not "1e-06", which it keeps as a string); yaml-cpp reads both.
std::string yamlReal(double v) {
  std::string s = formatParameterNumber(v);
  if (s.find_first_of(".ni") != std::string::npos) return s;  // has a '.', or inf / nan
  const std::size_t e = s.find('e');
  return e == std::string::npos ? s + ".0" : s.insert(e, ".0");
}

std::string yamlText(const std::string& value) {
  const bool plain = !value.empty() &&
                     value.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                             "0123456789_./-") == std::string::npos &&
                     !std::isdigit(static_cast<unsigned char>(value[0])) && value[0] != '-' &&
                     value != "true" && value != "false" && value != "yes" && value != "no" &&
                     value != "on" && value != "off" && value != "null";
  if (plain) return value;
  std::string quoted = "\"";
  for (const char c : value) quoted += (c == '"' || c == '\\') ? std::string("\\") + c : std::string(1, c);
  return quoted + "\"";
}

std::string meaningLine(const std::string& doc, const std::string& unit,
                        const std::string& allowed, const std::string& note) {
  std::string line = doc;
  if (!unit.empty()) line += ", " + unit;
  line += "; " + allowed;
  if (!note.empty()) line += "; " + note;
  return line;
}

}  // namespace parameter_detail
}  // namespace thermal_lidar_calibration
