#pragma once
// Where the people were in the pairs a calibration used: the paper's Table 5 shows that people
// bunched in one part of the image bias the result, and near people pin the translation while
// far ones pin the rotation. Counts person pixels of the masks on a grid and in the image's
// horizontal thirds, the LiDAR range of each person (near / far), their bearing in the camera,
// and the number of distinct places they stood (relative to the sensors).

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "thermal_lidar_calibration/core/calibration_pair.hpp"
#include "thermal_lidar_calibration/core/camera_model.hpp"
#include "thermal_lidar_calibration/core/extrinsic.hpp"

namespace thermal_lidar_calibration {

struct CoverageConfig {
  int grid_columns = 4;  // image grid for the person-pixel counts
  int grid_rows = 4;
  double near_far_split_m = 10.0;  // a person nearer than this (LiDAR range) is "near"
  double position_cell_m = 1.0;    // people closer than this (on the LiDAR's x-y) share a place
  void validate() const;           // throws std::invalid_argument naming the key and range
};

enum ImageThird : int { kLeftThird = 0, kCentreThird = 1, kRightThird = 2 };
const char* imageThirdName(int third);  // "left", "centre", "right"

struct Coverage {
  int grid_columns = 0, grid_rows = 0;
  std::vector<std::uint64_t> grid_pixels;       // person pixels per cell, row-major (row 0 = top)
  std::array<std::uint64_t, 3> third_pixels{};  // left, centre, right thirds of the width
  std::uint64_t person_pixels = 0;
  std::size_t pairs = 0;
  std::size_t people = 0;  // person clusters over all pairs
  std::size_t people_near = 0, people_far = 0;
  double near_far_split_m = 0.0;
  double range_min_m = 0.0, range_median_m = 0.0, range_max_m = 0.0;  // LiDAR range of people
  bool has_bearing = false;                                           // bearing needs an extrinsic
  double bearing_min_deg = 0.0, bearing_max_deg = 0.0;  // camera frame, + = right of the axis
  std::size_t distinct_positions = 0;

  double gridFraction(int row, int column) const;  // of all person pixels; 0 when none
  double thirdFraction(int third) const;
};

// `used`: indices of the pairs to count (all pairs when empty). `estimate`, when given, gives the
// people's bearing in the camera frame.
Coverage computeCoverage(const CameraModel& camera, const std::vector<CalibrationPair>& pairs,
                         const std::vector<std::size_t>& used,
                         const std::optional<Extrinsic>& estimate, const CoverageConfig& config);

}  // namespace thermal_lidar_calibration
