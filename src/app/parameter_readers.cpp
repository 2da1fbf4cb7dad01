#include "thermal_lidar_calibration/app/parameter_readers.hpp"

#include <cmath>
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

void readDoubleParameter(const ParameterSource& source, const std::string& key, double lo,
                         bool lo_open, double hi, double& target) {
  if (!source.has(key)) return;
  const auto v = source.getDouble(key);
  if (!v || !std::isfinite(*v) || *v > hi || (lo_open ? *v <= lo : *v < lo)) {
    throwBadParameter(source, key,
                      "must be a number in " + std::string(lo_open ? "(" : "[") +
                          formatParameterNumber(lo) + ", " + formatParameterNumber(hi) + "]");
  }
  target = *v;
}

void readStringParameter(const ParameterSource& source, const std::string& key,
                         std::string& target) {
  if (!source.has(key)) return;
  const auto v = source.getString(key);
  if (!v) throwBadParameter(source, key, "must be a string");
  target = *v;
}

void readBoolParameter(const ParameterSource& source, const std::string& key, bool& target) {
  if (!source.has(key)) return;
  const auto v = source.getBool(key);
  if (!v) throwBadParameter(source, key, "must be true or false");
  target = *v;
}

}  // namespace thermal_lidar_calibration
