#pragma once
// LiDAR person detection on one full scan: terrain-following ground (TerrainGround), above-ground
// points grouped on a 2-D grid (GridClusterer), objects too big for one person split by gaps
// (PCL Euclidean clustering) and by heads, and a person test per object (PersonShape). Works on
// unordered clouds: intensity and ring are not needed (KITTI .bin, merged clouds). Deterministic;
// one core; ~10 ms per 70k-point HDL-32E scan (bench/detection_benchmark.cpp).

#include "thermal_lidar_calibration/detection/grid_clusterer.hpp"
#include "thermal_lidar_calibration/detection/lidar_detector_config.hpp"
#include "thermal_lidar_calibration/detection/person_shape.hpp"
#include "thermal_lidar_calibration/detection/scan_view_top.hpp"
#include "thermal_lidar_calibration/detection/terrain_ground.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace thermal_lidar_calibration {
namespace detection {

struct LidarPerson {
  std::uint32_t label = 0;  // 1..n, nearest first
  Eigen::Vector3f centroid = Eigen::Vector3f::Zero();  // sensor frame, m
  Eigen::Vector3f size = Eigen::Vector3f::Zero();      // extent along the sensor's x, y, z, m
  int point_count = 0;
  float range_m = 0;   // horizontal distance from the sensor
  float height_m = 0;  // top above the local ground
  float width_m = 0;   // across the line of sight
  PersonShape shape;   // everything the person test measured (detect_people --explain prints it)
};

// An object (or a part of one) that failed the person test, for tuning.
struct RejectedObject {
  PersonShape shape;
  ShapeVerdict verdict = ShapeVerdict::kPerson;
  std::vector<int> indices;  // into the input
};

struct LidarDetection {
  std::vector<Eigen::Vector3f> points;  // the points on people, sensor frame
  std::vector<std::uint32_t> labels;    // one per point: its person's label
  std::vector<int> indices;             // one per point: its index in the input
  std::vector<LidarPerson> people;      // in label order
  // Diagnostics of the scan.
  double tilt_deg = 0;         // mount tilt removed by the levelling (0 if not levelled)
  double sensor_height_m = 0;  // above the levelling plane
  int objects = 0;             // above-ground objects considered
  bool view_top_found = false;  // the top of the scan's view (scan_view_top.hpp), when found
  double view_top_elevation_deg = 0;
  double view_top_offset_m = 0;
  std::vector<RejectedObject> rejected;  // objects and parts judged not a person (not split further)
};

class LidarPersonDetector {
 public:
  // Throws std::invalid_argument (from config.validate()) on a bad configuration.
  explicit LidarPersonDetector(const LidarDetectorConfig& config = {});

  // points: sensor frame (x, y, z in m; z roughly up). Non-finite points are skipped. Keeps
  // scratch buffers between calls: one detector per thread.
  LidarDetection detect(const std::vector<Eigen::Vector3f>& points);

  // The ground estimate of the last detect() (levelled points, heights), for inspection.
  const TerrainGround& ground() const { return ground_; }
  const LidarDetectorConfig& config() const { return config_; }

 private:
  // Judges an object (points: the input, sensor frame) and splits it when it may hold people.
  void explainObject(const std::vector<Eigen::Vector3f>& points, const std::vector<int>& object, int depth,
                     std::vector<std::vector<int>>* people, std::vector<RejectedObject>* rejected) const;
  PersonShape shapeOf(const std::vector<Eigen::Vector3f>& points, const std::vector<int>& object) const;
  // judgeShape, then judgeSampling on its rows for an object that passed it.
  ShapeVerdict judgeObject(const std::vector<Eigen::Vector3f>& points, const std::vector<int>& object,
                           const PersonShape& shape) const;

  LidarDetectorConfig config_;
  TerrainGround ground_;
  ScanViewTop view_top_;
  GridClusterer grid_;
};

}  // namespace detection
}  // namespace thermal_lidar_calibration
