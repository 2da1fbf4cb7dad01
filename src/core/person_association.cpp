#include "thermal_lidar_calibration/core/person_association.hpp"

#include "thermal_lidar_calibration/core/person_counter.hpp"
#include "thermal_lidar_calibration/core/person_timing.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>

namespace thermal_lidar_calibration {
namespace {

// The region a pixel shows, or the nearest one within `tolerance_px` (the first in scan order
// among equally near ones); 0 for none.
int regionAt(const cv::Mat& regions, int u, int v, double tolerance_px) {
  const int here = regions.at<std::uint16_t>(v, u);
  if (here != 0 || tolerance_px < 1.0) return here;
  const int reach = static_cast<int>(std::floor(tolerance_px));
  const double limit = tolerance_px * tolerance_px;
  int best = 0;
  double best_d2 = limit + 1.0;
  for (int dv = -reach; dv <= reach; ++dv) {
    const int y = v + dv;
    if (y < 0 || y >= regions.rows) continue;
    const std::uint16_t* row = regions.ptr<std::uint16_t>(y);
    for (int du = -reach; du <= reach; ++du) {
      const int x = u + du;
      if (x < 0 || x >= regions.cols || row[x] == 0) continue;
      const double d2 = static_cast<double>(du * du + dv * dv);
      if (d2 <= limit && d2 < best_d2) {
        best_d2 = d2;
        best = row[x];
      }
    }
  }
  return best;
}

// Per cluster: the points in view and how many of them land on each region.
struct ClusterHits {
  int points = 0;
  int in_view = 0;
  std::map<int, int> on_region;
  double share(int region) const {
    const auto it = on_region.find(region);
    return it == on_region.end() || in_view == 0 ? 0.0 : static_cast<double>(it->second) / in_view;
  }
};

}  // namespace

const ParameterRanges<AssociationConfig>& AssociationConfig::ranges() {
  static const auto ranges = ParameterRanges<AssociationConfig>()
      .add("association_min_overlap", &AssociationConfig::min_overlap, closedRange(0, 1))
      .add("association_margin", &AssociationConfig::margin, closedRange(0, 1))
      .add("association_tolerance_px", &AssociationConfig::tolerance_px, closedRange(0, 100))
      .add("min_points_in_view", &AssociationConfig::min_points_in_view, IntRange{1, 1000000000})
      .add("association_max_rounds", &AssociationConfig::max_rounds, IntRange{1, 100});
  return ranges;
}

void AssociationConfig::validate() const { ranges().check(*this); }

FrameAssociation associateClusters(const CameraModel& camera, const cv::Mat& regions,
                                   const std::vector<Eigen::Vector3f>& points,
                                   const std::vector<std::int32_t>& labels, const Extrinsic& extrinsic,
                                   const AssociationConfig& config) {
  if (regions.type() != CV_16UC1 || regions.cols != camera.width || regions.rows != camera.height) {
    throw std::invalid_argument("associateClusters: the regions must be a CV_16UC1 image of the camera's size");
  }
  if (points.size() != labels.size()) {
    throw std::invalid_argument("associateClusters: every point needs exactly one label");
  }
  FrameAssociation out;
  double max_region = 0.0;
  cv::minMaxLoc(regions, nullptr, &max_region);
  out.regions = static_cast<int>(max_region);

  const Eigen::Matrix3d R = extrinsic.rotationMatrix();
  std::map<std::int32_t, ClusterHits> clusters;
  for (std::size_t i = 0; i < points.size(); ++i) {
    ClusterHits& hits = clusters[labels[i]];
    ++hits.points;
    const Eigen::Vector3d p = R * points[i].cast<double>() + extrinsic.translation;
    if (!(p.z() > 0.0)) continue;
    const Eigen::Vector2d uv = camera.project(p);
    if (!uv.allFinite()) continue;
    const long u = std::lround(uv.x()), v = std::lround(uv.y());
    if (u < 0 || v < 0 || u >= camera.width || v >= camera.height) continue;
    ++hits.in_view;
    const int region = regionAt(regions, static_cast<int>(u), static_cast<int>(v), config.tolerance_px);
    if (region != 0) ++hits.on_region[region];
  }
  out.clusters = static_cast<int>(clusters.size());

  // Each cluster's best region, if it wins by the margin over the others.
  std::vector<ClusterMatch> candidates;
  for (const auto& [label, hits] : clusters) {
    if (hits.in_view < config.min_points_in_view || 2 * hits.in_view < hits.points) continue;
    ClusterMatch m;
    m.label = label;
    for (const auto& [region, n] : hits.on_region) {
      const double share = hits.share(region);
      if (share > m.overlap) {
        m.second = m.overlap;
        m.overlap = share;
        m.region = region;
      } else if (share > m.second) {
        m.second = share;
      }
    }
    if (m.region != 0 && m.overlap >= config.min_overlap && m.overlap - m.second >= config.margin) {
      candidates.push_back(m);
    }
  }
  // And the region's side: no other cluster may come within the margin of it on that region
  // (two clusters on one region, or one reaching over from beside it, leave it unmatched).
  for (const ClusterMatch& m : candidates) {
    bool clear = true;
    for (const auto& [label, hits] : clusters) {
      if (label != m.label && hits.share(m.region) > m.overlap - config.margin) clear = false;
    }
    if (clear) out.matches.push_back(m);
  }
  return out;
}

FrameAssociation associateFrame(const CameraModel& camera, const CalibrationPair& frame,
                                const Extrinsic& extrinsic, std::optional<double> time_offset_s,
                                const AssociationConfig& config) {
  if (!time_offset_s) return associateClusters(camera, frame.regions, frame.points, frame.labels, extrinsic, config);
  return associateClusters(camera, frame.regions, pointsAtImageTime(frame, *time_offset_s), frame.labels,
                           extrinsic, config);
}

std::optional<CalibrationPair> associatedPair(const CalibrationPair& frame, const FrameAssociation& association) {
  if (association.matches.empty()) return std::nullopt;
  std::vector<std::int32_t> keep;
  for (const ClusterMatch& m : association.matches) keep.push_back(m.label);  // by increasing label
  const auto kept = [&](std::int32_t label) { return std::binary_search(keep.begin(), keep.end(), label); };

  CalibrationPair pair;
  pair.stamp_s = frame.stamp_s;
  pair.mask = frame.mask.empty() ? binarizeMask(frame.regions) : frame.mask;
  pair.image = frame.image;
  pair.cloud_stamp_s = frame.cloud_stamp_s;
  pair.turn_rate_rps = frame.turn_rate_rps;
  pair.rule = PairRule::kAssociation;
  pair.candidate_index = frame.candidate_index;
  pair.people = static_cast<int>(keep.size());
  const bool times = frame.point_time_s.size() == frame.points.size();
  const bool velocities = frame.point_velocity.size() == frame.points.size();
  for (std::size_t i = 0; i < frame.points.size(); ++i) {
    if (!kept(frame.labels[i])) continue;
    pair.points.push_back(frame.points[i]);
    pair.labels.push_back(frame.labels[i]);
    if (times) pair.point_time_s.push_back(frame.point_time_s[i]);
    if (velocities) pair.point_velocity.push_back(frame.point_velocity[i]);
  }
  for (const PersonMotion& m : frame.motion) {
    if (kept(m.label)) pair.motion.push_back(m);
  }
  return pair;
}

}  // namespace thermal_lidar_calibration
