#pragma once
// The allowed range of each parameter, written once: beside the config struct whose field it
// limits. Each config lists its ranged fields in a static ranges(); its validate() checks them
// (so the ROS-free libraries refuse a bad value without any parameter table) and then the rules
// across keys; the parameter table's row for the key reads the same range to document it and to
// report a bad value in the user's terms (app/parameters/parameter_table.hpp). Keys no config
// checks (the node's, the sync settings) have their range in their row alone.
//
// The library's wording: "parameter 'population_size' = 1: must be in [2, 100000]".

#include <any>
#include <cmath>
#include <functional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

namespace thermal_lidar_calibration {

// Allowed values of a number key.
struct IntRange {
  long long lo;
  long long hi;  // std::numeric_limits<long long>::max() = no upper bound
};
struct RealRange {
  double lo;
  double hi;
  bool lo_open;  // (lo, hi] instead of [lo, hi]
};
inline RealRange closedRange(double lo, double hi) { return {lo, hi, false}; }   // [lo, hi]
inline RealRange aboveRange(double lo, double hi) { return {lo, hi, true}; }     // (lo, hi]

// Throws std::invalid_argument("parameter 'key' = value: must be in [lo, hi]"), "(lo, hi]" when
// lo_open. For the rules whose bound is another key (a minimum step below the initial one).
template <typename T>
void requireRange(const char* key, T value, T lo, T hi, bool lo_open = false) {
  const bool ok = std::isfinite(static_cast<double>(value)) &&
                  (lo_open ? value > lo : value >= lo) && value <= hi;
  if (!ok) {
    std::ostringstream s;
    s << "parameter '" << key << "' = " << value << ": must be in " << (lo_open ? "(" : "[")
      << lo << ", " << hi << "]";
    throw std::invalid_argument(s.str());
  }
}

// A rule across two keys: lo < hi (strict) or lo <= hi.
inline void requireOrdered(const char* lo_key, double lo, const char* hi_key, double hi, bool strict) {
  if (strict ? lo < hi : lo <= hi) return;
  std::ostringstream s;
  s << "parameters '" << lo_key << "' = " << lo << " and '" << hi_key << "' = " << hi << ": " << lo_key
    << (strict ? " must be below " : " must not exceed ") << hi_key;
  throw std::invalid_argument(s.str());
}

// The ranged fields of one config struct, in the order validate() checks them:
//   static const ParameterRanges<EvolutionConfig>& ranges() {
//     static const auto r = ParameterRanges<EvolutionConfig>()
//         .add("population_size", &EvolutionConfig::population_size, IntRange{2, 100000})
//         .add("sigma_rot_rad", &EvolutionConfig::sigma_rot_rad, aboveRange(0, 3.5));
//     return r;
//   }
template <typename Config>
class ParameterRanges {
 public:
  template <typename Int, typename = std::enable_if_t<std::is_integral_v<Int>>>
  ParameterRanges add(const char* key, Int Config::*field, IntRange range) && {
    entries_.push_back({key, field, range, [key, field, range](const Config& c) {
                          requireRange<long long>(key, c.*field, range.lo, range.hi);
                        }});
    return std::move(*this);
  }
  ParameterRanges add(const char* key, double Config::*field, RealRange range) && {
    entries_.push_back({key, field, range, [key, field, range](const Config& c) {
                          requireRange<double>(key, c.*field, range.lo, range.hi, range.lo_open);
                        }});
    return std::move(*this);
  }

  // Throws std::invalid_argument on the first field outside its range.
  void check(const Config& c) const {
    for (const auto& e : entries_) e.check(c);
  }

  // The range of `field`, listed under `key`. std::logic_error when it is not listed so (a table
  // row naming a key its config does not range, or another field).
  template <typename Int>
  IntRange of(const std::string& key, Int Config::*field) const {
    return std::get<IntRange>(find(key, field).range);
  }
  RealRange of(const std::string& key, double Config::*field) const {
    return std::get<RealRange>(find(key, field).range);
  }

 private:
  struct Entry {
    std::string key;
    std::any field;  // the member pointer
    std::variant<IntRange, RealRange> range;
    std::function<void(const Config&)> check;
  };

  template <typename Field>
  const Entry& find(const std::string& key, Field field) const {
    for (const auto& e : entries_) {
      const Field* f = std::any_cast<Field>(&e.field);
      if (e.key == key && f && *f == field) return e;
    }
    throw std::logic_error("parameter ranges: no range for '" + key + "' on this field");
  }

  std::vector<Entry> entries_;
};

}  // namespace thermal_lidar_calibration
