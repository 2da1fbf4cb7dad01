#include "thermal_lidar_calibration/detection/grid_clusterer.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace thermal_lidar_calibration {
namespace detection {

GridClusterer::GridClusterer(double cell_m, double half_extent_m)
    : cell_m_(static_cast<float>(cell_m)), half_extent_m_(static_cast<float>(half_extent_m)) {
  if (!(cell_m > 0) || !(half_extent_m > 0)) throw std::invalid_argument("GridClusterer: cell and extent must be > 0");
  side_ = static_cast<int>(std::ceil(2.0 * half_extent_m / cell_m));
  slot_of_cell_.assign(static_cast<std::size_t>(side_) * side_, -1);
}

int GridClusterer::find(int slot) {
  while (parent_[slot] != slot) {
    parent_[slot] = parent_[parent_[slot]];
    slot = parent_[slot];
  }
  return slot;
}

std::vector<std::vector<int>> GridClusterer::cluster(const std::vector<Eigen::Vector3f>& levelled,
                                                     const std::vector<int>& indices) {
  cell_of_slot_.clear();
  std::vector<int> slot_of_point(indices.size(), -1);
  for (std::size_t j = 0; j < indices.size(); ++j) {
    const Eigen::Vector3f& p = levelled[indices[j]];
    const int cx = static_cast<int>(std::floor((p.x() + half_extent_m_) / cell_m_));
    const int cy = static_cast<int>(std::floor((p.y() + half_extent_m_) / cell_m_));
    if (cx < 0 || cy < 0 || cx >= side_ || cy >= side_) continue;
    int& slot = slot_of_cell_[static_cast<std::size_t>(cy) * side_ + cx];
    if (slot < 0) {
      slot = static_cast<int>(cell_of_slot_.size());
      cell_of_slot_.push_back(cy * side_ + cx);
    }
    slot_of_point[j] = slot;
  }
  const int slots = static_cast<int>(cell_of_slot_.size());
  parent_.resize(slots);
  for (int s = 0; s < slots; ++s) parent_[s] = s;
  // Union with the occupied neighbours ahead (the other four are visited from their side).
  static const int kAhead[4][2] = {{1, 0}, {-1, 1}, {0, 1}, {1, 1}};
  for (int s = 0; s < slots; ++s) {
    const int cx = cell_of_slot_[s] % side_, cy = cell_of_slot_[s] / side_;
    for (const auto& d : kAhead) {
      const int nx = cx + d[0], ny = cy + d[1];
      if (nx < 0 || ny < 0 || nx >= side_ || ny >= side_) continue;
      const int other = slot_of_cell_[static_cast<std::size_t>(ny) * side_ + nx];
      if (other < 0) continue;
      const int a = find(s), b = find(other);
      if (a != b) parent_[std::max(a, b)] = std::min(a, b);
    }
  }
  std::vector<int> cluster_of_root(slots, -1);
  std::vector<std::vector<int>> clusters;
  for (std::size_t j = 0; j < indices.size(); ++j) {
    if (slot_of_point[j] < 0) continue;
    const int root = find(slot_of_point[j]);
    if (cluster_of_root[root] < 0) {
      cluster_of_root[root] = static_cast<int>(clusters.size());
      clusters.emplace_back();
    }
    clusters[cluster_of_root[root]].push_back(indices[j]);
  }
  for (int cell : cell_of_slot_) slot_of_cell_[cell] = -1;
  return clusters;
}

}  // namespace detection
}  // namespace thermal_lidar_calibration
