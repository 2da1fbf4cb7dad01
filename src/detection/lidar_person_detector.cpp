#include "thermal_lidar_calibration/detection/lidar_person_detector.hpp"

#include "thermal_lidar_calibration/detection/object_splitter.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace thermal_lidar_calibration {
namespace detection {
namespace {

// Objects are gathered a little beyond the range limit so that a person whose centre is just
// inside still has all of its points.
constexpr double kRangeMarginM = 1.0;

const LidarDetectorConfig& validated(const LidarDetectorConfig& config) {
  config.validate();
  return config;
}

// A failed person test that splitting may cure: the object is bigger than one person.
bool mayHoldPeople(ShapeVerdict verdict, const PersonShape& shape, const LidarPersonConfig& c) {
  // A tree cut by the view's top with a person beside it: the person is a part of its own.
  const bool too_big = verdict == ShapeVerdict::kTooWide || verdict == ShapeVerdict::kTooDeep ||
                       verdict == ShapeVerdict::kTooTall || verdict == ShapeVerdict::kTooSquat ||
                       verdict == ShapeVerdict::kCutByViewTop;
  return too_big && shape.width_m <= c.max_split_extent_m && shape.depth_m <= c.max_split_extent_m &&
         shape.top_m >= c.min_height_m;
}

}  // namespace

LidarPersonDetector::LidarPersonDetector(const LidarDetectorConfig& config)
    : config_(validated(config)),
      ground_(config.ground),
      grid_(config.person.cluster_cell_m, config.person.max_range_m + kRangeMarginM) {}

PersonShape LidarPersonDetector::shapeOf(const std::vector<Eigen::Vector3f>& points,
                                         const std::vector<int>& object) const {
  PersonShape shape = measureShape(ground_.levelledPoints(), ground_.heights(), object);
  if (config_.person.view_top_margin_deg > 0.0) {
    shape.view_top_gap_deg = static_cast<float>(view_top_.gapBelowDeg(points, object));
  }
  return shape;
}

ShapeVerdict LidarPersonDetector::judgeObject(const std::vector<Eigen::Vector3f>& points, const std::vector<int>& object,
                                              const PersonShape& shape) const {
  const ShapeVerdict verdict = judgeShape(shape, config_.person);
  if (verdict != ShapeVerdict::kPerson) return verdict;
  // The rows are measured only for the few objects that passed everything else.
  return judgeSampling(shape, measureRows(points, object, shape.range_m), config_.person, config_.ground.tolerance_m);
}

void LidarPersonDetector::explainObject(const std::vector<Eigen::Vector3f>& points, const std::vector<int>& object,
                                        int depth, std::vector<std::vector<int>>* people,
                                        std::vector<RejectedObject>* rejected) const {
  const LidarPersonConfig& c = config_.person;
  const auto& levelled = ground_.levelledPoints();
  const auto& heights = ground_.heights();
  const PersonShape shape = shapeOf(points, object);
  const ShapeVerdict verdict = judgeObject(points, object, shape);
  if (verdict == ShapeVerdict::kPerson) {
    people->push_back(object);
    return;
  }
  if (depth >= 2 || !mayHoldPeople(verdict, shape, c)) {
    rejected->push_back({shape, verdict, object});
    return;
  }
  // First by gaps; a part that is still too big, or an object without gaps, by heads.
  std::vector<std::vector<int>> parts = depth == 0 ? splitByGaps(levelled, object, c.split_tolerance_m)
                                                   : std::vector<std::vector<int>>{};
  if (parts.size() <= 1) {
    parts = splitByHeads(levelled, heights, object, c.split_tolerance_m, c.head_dip_m);
    if (parts.size() <= 1) {
      rejected->push_back({shape, verdict, object});
      return;
    }
    for (const auto& part : parts) {
      const PersonShape part_shape = shapeOf(points, part);
      const ShapeVerdict part_verdict = judgeObject(points, part, part_shape);
      if (part_verdict == ShapeVerdict::kPerson) {
        people->push_back(part);
      } else {
        rejected->push_back({part_shape, part_verdict, part});
      }
    }
    return;
  }
  for (const auto& part : parts) explainObject(points, part, depth + 1, people, rejected);
}

LidarDetection LidarPersonDetector::detect(const std::vector<Eigen::Vector3f>& points) {
  const LidarPersonConfig& c = config_.person;
  const double reach = c.max_range_m + kRangeMarginM;
  ground_.estimate(points, reach);
  LidarDetection result;
  if (c.view_top_margin_deg > 0.0) {
    view_top_.fit(points, ground_.heights(), static_cast<float>(config_.ground.tolerance_m));
    result.view_top_found = view_top_.found();
    result.view_top_elevation_deg = view_top_.elevationDeg();
    result.view_top_offset_m = view_top_.offsetM();
  }
  result.tilt_deg = ground_.tiltDeg();
  result.sensor_height_m = ground_.sensorHeightM();

  const auto& levelled = ground_.levelledPoints();
  const auto& heights = ground_.heights();
  const float ground_tolerance = static_cast<float>(config_.ground.tolerance_m);
  const float top = static_cast<float>(c.max_object_height_m);
  const float near2 = static_cast<float>(std::max(0.0, c.min_range_m - kRangeMarginM));
  std::vector<int> above;
  above.reserve(points.size() / 4);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const float h = heights[i];
    if (!(h > ground_tolerance && h <= top)) continue;  // NaN fails too
    if (levelled[i].head<2>().squaredNorm() < near2 * near2) continue;
    above.push_back(static_cast<int>(i));
  }
  const std::vector<std::vector<int>> objects = grid_.cluster(levelled, above);
  result.objects = static_cast<int>(objects.size());

  std::vector<std::vector<int>> people;
  for (const auto& object : objects) {
    // Cheap rejections before any measuring: too few points for a person anywhere in range.
    if (static_cast<int>(object.size()) < c.min_points) continue;
    explainObject(points, object, 0, &people, &result.rejected);
  }

  // Labels nearest first (ties by first point index): deterministic whatever the input order.
  std::vector<std::pair<float, int>> order;
  std::vector<PersonShape> shapes;
  for (std::size_t k = 0; k < people.size(); ++k) {
    shapes.push_back(shapeOf(points, people[k]));
    order.emplace_back(shapes.back().range_m, static_cast<int>(k));
  }
  std::sort(order.begin(), order.end(), [&](const auto& a, const auto& b) {
    return a.first != b.first ? a.first < b.first : people[a.second].front() < people[b.second].front();
  });
  for (std::size_t rank = 0; rank < order.size(); ++rank) {
    const int k = order[rank].second;
    LidarPerson person;
    person.label = static_cast<std::uint32_t>(rank + 1);
    Eigen::Vector3f lo = Eigen::Vector3f::Constant(std::numeric_limits<float>::infinity());
    Eigen::Vector3f hi = -lo;
    Eigen::Vector3f sum = Eigen::Vector3f::Zero();
    for (int i : people[k]) {
      const Eigen::Vector3f& p = points[i];
      sum += p;
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
      result.points.push_back(p);
      result.labels.push_back(person.label);
      result.indices.push_back(i);
    }
    person.point_count = static_cast<int>(people[k].size());
    person.centroid = sum / static_cast<float>(person.point_count);
    person.size = hi - lo;
    person.range_m = shapes[k].range_m;
    person.height_m = shapes[k].top_m;
    person.width_m = shapes[k].width_m;
    person.shape = shapes[k];
    result.people.push_back(person);
  }
  return result;
}

}  // namespace detection
}  // namespace thermal_lidar_calibration
