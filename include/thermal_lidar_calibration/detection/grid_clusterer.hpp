#pragma once
// Groups above-ground points into objects by 8-connected occupancy of a 2-D grid in the levelled
// frame (Bogoslavskyi & Stachniss 2016 cluster a range image; a horizontal grid does the same
// for unordered clouds). Linear in the number of points: no KD-tree over the whole scan.

#include <Eigen/Core>

#include <vector>

namespace thermal_lidar_calibration {
namespace detection {

class GridClusterer {
 public:
  // cell_m: cell side; half_extent_m: the grid covers [-half_extent, half_extent]^2 (points
  // outside are left out).
  GridClusterer(double cell_m, double half_extent_m);

  // Clusters of `indices` (into `levelled`), each in input order; clusters ordered by their
  // first point. Deterministic.
  std::vector<std::vector<int>> cluster(const std::vector<Eigen::Vector3f>& levelled,
                                        const std::vector<int>& indices);

 private:
  int find(int slot);

  float cell_m_;
  float half_extent_m_;
  int side_;
  std::vector<int> slot_of_cell_;  // -1 = empty; reset after each call via the touched cells
  std::vector<int> cell_of_slot_;
  std::vector<int> parent_;
};

}  // namespace detection
}  // namespace thermal_lidar_calibration
