#include "thermal_lidar_calibration/core/coverage.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>

namespace thermal_lidar_calibration {

void CoverageConfig::validate() const {
  if (grid_columns < 1 || grid_columns > 64 || grid_rows < 1 || grid_rows > 64) {
    throw std::invalid_argument("coverage grid " + std::to_string(grid_columns) + "x" +
                                std::to_string(grid_rows) +
                                ": columns and rows must be in [1, 64]");
  }
  if (!(near_far_split_m > 0.0 && near_far_split_m <= 1000.0)) {
    throw std::invalid_argument("parameter 'coverage_near_far_split_m' = " +
                                std::to_string(near_far_split_m) + ": must be in (0, 1000]");
  }
  if (!(position_cell_m > 0.0 && position_cell_m <= 100.0)) {
    throw std::invalid_argument("parameter 'coverage_position_cell_m' = " +
                                std::to_string(position_cell_m) + ": must be in (0, 100]");
  }
}

const char* imageThirdName(int third) {
  switch (third) {
    case kLeftThird:
      return "left";
    case kCentreThird:
      return "centre";
    default:
      return "right";
  }
}

double Coverage::gridFraction(int row, int column) const {
  if (person_pixels == 0) return 0.0;
  return static_cast<double>(grid_pixels[static_cast<std::size_t>(row * grid_columns + column)]) /
         static_cast<double>(person_pixels);
}

double Coverage::thirdFraction(int third) const {
  if (person_pixels == 0) return 0.0;
  return static_cast<double>(third_pixels[static_cast<std::size_t>(third)]) /
         static_cast<double>(person_pixels);
}

namespace {

// Person pixels per grid cell and per third, from the masks (no extrinsic needed). Cell c
// spans [c * size / cells, (c + 1) * size / cells) in each direction.
void countPixels(const cv::Mat& mask, Coverage& c) {
  const auto edge = [](int k, int cells, int size) { return k * size / cells; };
  for (int row = 0; row < c.grid_rows; ++row) {
    for (int column = 0; column < c.grid_columns; ++column) {
      const cv::Rect cell(
          cv::Point(edge(column, c.grid_columns, mask.cols), edge(row, c.grid_rows, mask.rows)),
          cv::Point(edge(column + 1, c.grid_columns, mask.cols),
                    edge(row + 1, c.grid_rows, mask.rows)));
      c.grid_pixels[static_cast<std::size_t>(row * c.grid_columns + column)] +=
          static_cast<std::uint64_t>(cv::countNonZero(mask(cell)));
    }
  }
  std::uint64_t all = 0;
  for (int third = 0; third < 3; ++third) {
    const cv::Rect band(cv::Point(edge(third, 3, mask.cols), 0),
                        cv::Point(edge(third + 1, 3, mask.cols), mask.rows));
    const auto n = static_cast<std::uint64_t>(cv::countNonZero(mask(band)));
    c.third_pixels[static_cast<std::size_t>(third)] += n;
    all += n;
  }
  c.person_pixels += all;
}

// The centroid of each person (label) of a pair, LiDAR frame.
std::vector<Eigen::Vector3d> personCentroids(const CalibrationPair& pair) {
  std::map<std::int32_t, std::pair<Eigen::Vector3d, int>> sums;
  for (std::size_t i = 0; i < pair.points.size(); ++i) {
    const std::int32_t label = i < pair.labels.size() ? pair.labels[i] : 0;
    auto& s = sums.try_emplace(label, Eigen::Vector3d::Zero(), 0).first->second;
    s.first += pair.points[i].cast<double>();
    ++s.second;
  }
  std::vector<Eigen::Vector3d> out;
  for (const auto& kv : sums) out.push_back(kv.second.first / kv.second.second);
  return out;
}

}  // namespace

Coverage computeCoverage(const CameraModel& camera, const std::vector<CalibrationPair>& pairs,
                         const std::vector<std::size_t>& used,
                         const std::optional<Extrinsic>& estimate, const CoverageConfig& config) {
  config.validate();
  Coverage c;
  c.grid_columns = config.grid_columns;
  c.grid_rows = config.grid_rows;
  c.grid_pixels.assign(static_cast<std::size_t>(c.grid_columns * c.grid_rows), 0);
  c.near_far_split_m = config.near_far_split_m;
  std::vector<std::size_t> indices = used;
  if (indices.empty()) {
    indices.resize(pairs.size());
    std::iota(indices.begin(), indices.end(), std::size_t{0});
  }
  std::vector<double> ranges, bearings;
  std::set<std::pair<long, long>> places;
  const Eigen::Matrix3d R = estimate ? estimate->rotationMatrix() : Eigen::Matrix3d::Identity();
  for (std::size_t i : indices) {
    const CalibrationPair& pair = pairs.at(i);
    if (pair.mask.cols != camera.width || pair.mask.rows != camera.height ||
        pair.mask.type() != CV_8UC1) {
      throw std::invalid_argument("coverage: pair " + std::to_string(i) +
                                  " has a mask that is not 8-bit of the camera's size");
    }
    ++c.pairs;
    countPixels(pair.mask, c);
    for (const Eigen::Vector3d& p : personCentroids(pair)) {
      const double range = p.norm();
      ranges.push_back(range);
      ++(range < config.near_far_split_m ? c.people_near : c.people_far);
      places.emplace(std::lround(std::floor(p.x() / config.position_cell_m)),
                     std::lround(std::floor(p.y() / config.position_cell_m)));
      if (estimate) {
        const Eigen::Vector3d q = R * p + estimate->translation;
        bearings.push_back(std::atan2(q.x(), q.z()) * 180.0 / M_PI);
      }
    }
  }
  c.people = ranges.size();
  c.distinct_positions = places.size();
  if (!ranges.empty()) {
    std::sort(ranges.begin(), ranges.end());
    c.range_min_m = ranges.front();
    c.range_max_m = ranges.back();
    const std::size_t m = ranges.size() / 2;
    c.range_median_m = ranges.size() % 2 ? ranges[m] : 0.5 * (ranges[m - 1] + ranges[m]);
  }
  if (!bearings.empty()) {
    c.has_bearing = true;
    const auto [lo, hi] = std::minmax_element(bearings.begin(), bearings.end());
    c.bearing_min_deg = *lo;
    c.bearing_max_deg = *hi;
  }
  return c;
}

}  // namespace thermal_lidar_calibration
