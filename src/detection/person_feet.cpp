#include "thermal_lidar_calibration/detection/person_feet.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace thermal_lidar_calibration {
namespace detection {
namespace {

struct Footprint {
  Eigen::Vector2f axis = Eigen::Vector2f::Zero();
  float radius = 0.f;   // legs' farthest point from the axis, plus the margin
  float nearest = 0.f;  // legs' nearest horizontal range from the sensor, less the margin
  bool valid = false;
};

Footprint footprintOf(const std::vector<Eigen::Vector3f>& levelled, const std::vector<float>& heights,
                      const std::vector<int>& person) {
  Footprint f;
  int legs = 0;
  for (const int i : person) {
    if (heights[i] <= kLegsTopM) {
      f.axis += levelled[i].head<2>();
      ++legs;
    }
  }
  if (legs == 0) return f;
  f.axis /= static_cast<float>(legs);
  f.nearest = std::numeric_limits<float>::infinity();
  for (const int i : person) {
    if (heights[i] > kLegsTopM) continue;
    f.radius = std::max(f.radius, (levelled[i].head<2>() - f.axis).norm());
    f.nearest = std::min(f.nearest, levelled[i].head<2>().norm());
  }
  f.radius += kFootMarginM;
  f.nearest -= kFootMarginM;
  f.valid = true;
  return f;
}

}  // namespace

std::vector<std::vector<int>> feetUnder(const std::vector<Eigen::Vector3f>& levelled,
                                        const std::vector<float>& heights,
                                        const std::vector<std::vector<int>>& people, float min_height_m,
                                        float max_height_m) {
  std::vector<std::vector<int>> feet(people.size());
  if (people.empty() || !(max_height_m > min_height_m)) return feet;
  std::vector<Footprint> prints;
  prints.reserve(people.size());
  for (const auto& person : people) prints.push_back(footprintOf(levelled, heights, person));
  for (std::size_t i = 0; i < heights.size(); ++i) {
    const float h = heights[i];
    if (!(h > min_height_m && h <= max_height_m)) continue;  // NaN fails too
    const Eigen::Vector2f xy = levelled[i].head<2>();
    const float range = xy.norm();
    int best = -1;
    float best_distance = std::numeric_limits<float>::infinity();
    for (std::size_t k = 0; k < prints.size(); ++k) {
      const Footprint& f = prints[k];
      if (!f.valid || range < f.nearest) continue;
      const float d = (xy - f.axis).norm();
      if (d <= f.radius && d < best_distance) {
        best = static_cast<int>(k);
        best_distance = d;
      }
    }
    if (best >= 0) feet[static_cast<std::size_t>(best)].push_back(static_cast<int>(i));
  }
  return feet;
}

}  // namespace detection
}  // namespace thermal_lidar_calibration
