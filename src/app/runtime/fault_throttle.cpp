#include "thermal_lidar_calibration/app/runtime/fault_throttle.hpp"

#include <cctype>
#include <cstdio>

namespace thermal_lidar_calibration {

std::string FaultThrottle::kindOf(const std::string& fault) {
  std::string kind;
  kind.reserve(fault.size());
  for (std::size_t i = 0; i < fault.size();) {
    if (!std::isdigit(static_cast<unsigned char>(fault[i]))) {
      kind.push_back(fault[i++]);
      continue;
    }
    // One number: digits with points and an exponent ("1.6e+09", "-0.5"): one '#'.
    if (!kind.empty() && (kind.back() == '-' || kind.back() == '+')) kind.pop_back();
    while (i < fault.size()) {
      const char c = fault[i];
      const bool exponent_sign = (c == '-' || c == '+') && (fault[i - 1] == 'e' || fault[i - 1] == 'E');
      if (!std::isdigit(static_cast<unsigned char>(c)) && c != '.' && c != 'e' && c != 'E' &&
          !exponent_sign) {
        break;
      }
      ++i;
    }
    kind.push_back('#');
  }
  return kind;
}

std::optional<std::uint64_t> FaultThrottle::admit(const std::string& fault, Clock::time_point now) {
  // Kinds are few in practice; the bound only guards against text that defeats kindOf.
  if (kinds_.size() > 256) kinds_.clear();
  const auto [it, first] = kinds_.try_emplace(kindOf(fault));
  Kind& kind = it->second;
  if (!first && now - kind.last_report < period_) {
    ++kind.held_back;
    return std::nullopt;
  }
  const std::uint64_t held_back = kind.held_back;
  kind.held_back = 0;
  kind.last_report = now;
  return held_back;
}

std::string FaultThrottle::heldBackText(std::uint64_t held_back) const {
  if (held_back == 0) return "";
  char text[96];
  std::snprintf(text, sizeof(text), " (and %llu more like it in the last %g s)",
                static_cast<unsigned long long>(held_back), periodS());
  return text;
}

}  // namespace thermal_lidar_calibration
