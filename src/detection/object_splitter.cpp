#include "thermal_lidar_calibration/detection/object_splitter.hpp"

#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>
#include <pcl/segmentation/extract_clusters.h>
// Compiled here from PCL's template, not linked from libpcl_segmentation (CMakeLists.txt says why).
#include <pcl/segmentation/impl/extract_clusters.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace thermal_lidar_calibration {
namespace detection {

std::vector<std::vector<int>> splitByGaps(const std::vector<Eigen::Vector3f>& levelled,
                                          const std::vector<int>& object, double tolerance_m) {
  pcl::PointCloud<pcl::PointXYZ>::Ptr flat(new pcl::PointCloud<pcl::PointXYZ>);
  flat->reserve(object.size());
  for (int i : object) flat->push_back(pcl::PointXYZ(levelled[i].x(), levelled[i].y(), 0.f));
  pcl::search::KdTree<pcl::PointXYZ>::Ptr tree(new pcl::search::KdTree<pcl::PointXYZ>);
  tree->setInputCloud(flat);
  pcl::EuclideanClusterExtraction<pcl::PointXYZ> extraction;
  extraction.setClusterTolerance(tolerance_m);
  extraction.setMinClusterSize(1);
  extraction.setMaxClusterSize(std::numeric_limits<int>::max());
  extraction.setSearchMethod(tree);
  extraction.setInputCloud(flat);
  std::vector<pcl::PointIndices> found;
  extraction.extract(found);
  std::vector<std::vector<int>> parts;
  parts.reserve(found.size());
  for (const pcl::PointIndices& c : found) {
    std::vector<int> part;
    part.reserve(c.indices.size());
    for (int j : c.indices) part.push_back(object[j]);
    std::sort(part.begin(), part.end());
    parts.push_back(std::move(part));
  }
  // PCL orders by size; equal sizes by first index, so the order never depends on the tree.
  std::stable_sort(parts.begin(), parts.end(), [](const std::vector<int>& a, const std::vector<int>& b) {
    return a.size() != b.size() ? a.size() > b.size() : a.front() < b.front();
  });
  return parts;
}

std::vector<std::vector<int>> splitByHeads(const std::vector<Eigen::Vector3f>& levelled,
                                           const std::vector<float>& heights, const std::vector<int>& object,
                                           double bin_m, double dip_m) {
  if (object.empty()) return {};
  Eigen::Vector2f centroid = Eigen::Vector2f::Zero();
  for (int i : object) centroid += levelled[i].head<2>();
  centroid /= static_cast<float>(object.size());
  const float r = centroid.norm();
  const Eigen::Vector2f along = r > 1e-6f ? Eigen::Vector2f(centroid / r) : Eigen::Vector2f(Eigen::Vector2f::UnitX());
  const Eigen::Vector2f across(-along.y(), along.x());
  std::vector<float> coord(object.size());
  float lo = std::numeric_limits<float>::infinity(), hi = -lo;
  for (std::size_t j = 0; j < object.size(); ++j) {
    coord[j] = levelled[object[j]].head<2>().dot(across);
    lo = std::min(lo, coord[j]);
    hi = std::max(hi, coord[j]);
  }
  const float bin = static_cast<float>(bin_m);
  const int bins = std::max(1, static_cast<int>((hi - lo) / bin) + 1);
  std::vector<float> profile(bins, 0.f);  // highest point per bin; an empty bin is ground (0)
  for (std::size_t j = 0; j < object.size(); ++j) {
    const int b = std::min(bins - 1, static_cast<int>((coord[j] - lo) / bin));
    profile[b] = std::max(profile[b], heights[object[j]]);
  }
  // Walk across: a valley splits when both the peak before it and the rise after it clear dip.
  const float dip = static_cast<float>(dip_m);
  std::vector<int> cuts;  // bin indices of the valleys
  float peak = profile[0], valley = profile[0];
  int valley_bin = 0;
  for (int b = 1; b < bins; ++b) {
    const float h = profile[b];
    if (peak - valley >= dip && h - valley >= dip) {
      cuts.push_back(valley_bin);
      peak = h;
      valley = h;
      valley_bin = b;
    } else if (h > peak) {
      peak = h;
      valley = h;
      valley_bin = b;
    } else if (h < valley) {
      valley = h;
      valley_bin = b;
    }
  }
  std::vector<std::vector<int>> parts(cuts.size() + 1);
  for (std::size_t j = 0; j < object.size(); ++j) {
    const int b = std::min(bins - 1, static_cast<int>((coord[j] - lo) / bin));
    // Points in a valley bin go to neither side's head: they are the seam.
    const auto part = static_cast<std::size_t>(std::upper_bound(cuts.begin(), cuts.end(), b - 1) - cuts.begin());
    if (std::binary_search(cuts.begin(), cuts.end(), b)) continue;
    parts[part].push_back(object[j]);
  }
  parts.erase(std::remove_if(parts.begin(), parts.end(), [](const std::vector<int>& p) { return p.empty(); }),
              parts.end());
  return parts;
}

}  // namespace detection
}  // namespace thermal_lidar_calibration
