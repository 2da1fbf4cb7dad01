#include "thermal_lidar_calibration/core/ring_ends.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

namespace thermal_lidar_calibration {
namespace {

// At most this fraction of a person's elevation span may lie within its runs: a spinning LiDAR's
// rings have next to no spread of their own, a person's span crosses the gaps between them
// (0.33-2 deg).
constexpr double kMaxCoveredFraction = 0.05;
// A ring's own spread of elevation, at most (the Ouster's offset beams move by ~0.01 deg across a
// person at 5 m).
constexpr double kMaxRingSpreadRad = 0.05 * 3.14159265358979 / 180.0;
// At least this fraction of a person's points must lie on rings for its rings to be scan lines.
constexpr double kMinOnRings = 0.5;

}  // namespace

std::vector<RingEnd> findRingEnds(const std::vector<Eigen::Vector3f>& points,
                                  const std::vector<std::int32_t>& labels, double ring_gap_rad, int min_points) {
  std::vector<RingEnd> ends;
  if (labels.size() != points.size()) return ends;
  struct Polar {
    double elevation, azimuth;
    std::uint32_t index;
  };
  // Azimuth about each person's own mean bearing, so that a person behind the sensor (where the
  // bearing wraps at +-180 deg) has its ends at the ends of its span too.
  std::map<std::int32_t, Eigen::Vector2d> bearing;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (labels[i] > 0 && points[i].allFinite()) {
      const Eigen::Vector2d direction(points[i].x(), points[i].y());
      if (direction.norm() > 0.0) {
        bearing.try_emplace(labels[i], Eigen::Vector2d::Zero()).first->second += direction.normalized();
      }
    }
  }
  std::map<std::int32_t, std::vector<Polar>> by_label;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (labels[i] <= 0) continue;
    const Eigen::Vector3f& p = points[i];
    const double ground = std::hypot(static_cast<double>(p.x()), static_cast<double>(p.y()));
    if (!(ground > 0.0) || !p.allFinite()) continue;
    const Eigen::Vector2d& b = bearing.at(labels[i]);
    const Eigen::Vector2d q(p.x(), p.y());
    by_label[labels[i]].push_back({std::atan2(static_cast<double>(p.z()), ground),
                                   std::atan2(b.x() * q.y() - b.y() * q.x(), b.dot(q)),
                                   static_cast<std::uint32_t>(i)});
  }
  for (auto& [label, polar] : by_label) {
    std::sort(polar.begin(), polar.end(), [](const Polar& a, const Polar& b) { return a.elevation < b.elevation; });
    std::vector<std::pair<std::size_t, std::size_t>> runs;  // [begin, end) of each elevation run
    double covered = 0.0;
    for (std::size_t begin = 0; begin < polar.size();) {
      std::size_t end = begin + 1;
      while (end < polar.size() && polar[end].elevation - polar[end - 1].elevation < ring_gap_rad) ++end;
      runs.emplace_back(begin, end);
      covered += polar[end - 1].elevation - polar[begin].elevation;
      begin = end;
    }
    // A spinning LiDAR puts a person's points on a few elevations: the runs cover a small part of
    // the person's elevation span. Points spread over it (a solid-state pattern, points resampled
    // or drawn at random heights) chain into runs whose extreme azimuths say nothing of where a
    // scan line leaves the person: such a person has no ends.
    const double span = polar.back().elevation - polar.front().elevation;
    if (covered > std::max(kMaxCoveredFraction * span, ring_gap_rad)) continue;
    // Sparse points at random heights also fall a few together by chance, spread over the gap;
    // a scan line's points share one elevation.
    const auto isRing = [&](std::size_t begin, std::size_t end) {
      return static_cast<int>(end - begin) >= min_points &&
             polar[end - 1].elevation - polar[begin].elevation <= kMaxRingSpreadRad;
    };
    // On a spinning LiDAR nearly every point of a person lies on such a ring. A few chance rings
    // among points at random heights (a sparse or solid-state cluster) are not scan lines: their
    // ends say nothing of the outline, and charged they pull the fit.
    std::vector<std::pair<std::size_t, std::size_t>> rings;
    std::size_t on_rings = 0;
    for (const auto& [begin, end] : runs) {
      if (!isRing(begin, end)) continue;
      rings.emplace_back(begin, end);
      on_rings += end - begin;
    }
    if (static_cast<double>(on_rings) < kMinOnRings * static_cast<double>(polar.size())) continue;
    for (const auto& [begin, end] : rings) {
      std::vector<Polar> ring(polar.begin() + static_cast<std::ptrdiff_t>(begin),
                              polar.begin() + static_cast<std::ptrdiff_t>(end));
      std::sort(ring.begin(), ring.end(), [](const Polar& a, const Polar& b) { return a.azimuth < b.azimuth; });
      ends.push_back({ring.front().index, ring[1].index});
      ends.push_back({ring.back().index, ring[ring.size() - 2].index});
    }
  }
  return ends;
}

namespace {

constexpr float kNoEdge = std::numeric_limits<float>::quiet_NaN();

// The region each cluster owns (0: none): the region most of its projected points fall in, with
// at least `min_inside` of them, and no other cluster owning it.
std::map<std::int32_t, int> ownRegions(const cv::Mat& regions, const std::vector<std::int32_t>& labels,
                                       const std::vector<Eigen::Vector2f>& pixels, double min_inside) {
  std::map<std::int32_t, std::map<int, int>> hits;
  std::map<std::int32_t, int> total;
  for (std::size_t i = 0; i < labels.size(); ++i) {
    if (labels[i] <= 0) continue;
    ++total[labels[i]];
    const Eigen::Vector2f& p = pixels[i];
    if (!p.allFinite()) continue;
    const int c = static_cast<int>(std::lround(p.x()));
    const int r = static_cast<int>(std::lround(p.y()));
    if (c < 0 || r < 0 || c >= regions.cols || r >= regions.rows) continue;
    const int region = regions.at<int>(r, c);
    if (region > 0) ++hits[labels[i]][region];
  }
  std::map<std::int32_t, int> owner;
  std::map<int, int> claims;
  for (const auto& [label, counts] : hits) {
    const auto best = std::max_element(counts.begin(), counts.end(),
                                       [](const auto& a, const auto& b) { return a.second < b.second; });
    if (best->second >= min_inside * total[label]) {
      owner[label] = best->first;
      ++claims[best->first];
    }
  }
  for (auto& [label, region] : owner) {
    if (claims[region] > 1) region = 0;  // two people in one region: neither outline is known
  }
  return owner;
}

// The outline of region `region`, whose bounding box is `box`: per row its outermost pixels on
// each side.
PersonOutline outlineOf(const cv::Mat& regions, int region, const cv::Rect& box, int clearance) {
  PersonOutline out;
  out.first_row = box.y;
  for (int row = box.y; row < box.y + box.height; ++row) {
    const int* r = regions.ptr<int>(row);
    int lo = -1, hi = -1;
    for (int c = box.x; c < box.x + box.width; ++c) {
      if (r[c] == region) {
        if (lo < 0) lo = c;
        hi = c;
      }
    }
    if (lo < 0) {  // a region of 8-connected pixels can skip a row only where it is diagonal
      out.left.push_back(kNoEdge);
      out.right.push_back(kNoEdge);
      continue;
    }
    // Usable when the image goes on beyond it and no other region lies within `clearance`.
    const auto usable = [&](int edge, int side) {
      for (int k = 1; k <= clearance + 1; ++k) {
        const int c = edge + side * k;
        if (c < 0 || c >= regions.cols) return false;
        if (k <= clearance && r[c] != 0 && r[c] != region) return false;
      }
      return true;
    };
    out.left.push_back(usable(lo, -1) ? static_cast<float>(lo) - 0.5f : kNoEdge);
    out.right.push_back(usable(hi, 1) ? static_cast<float>(hi) + 0.5f : kNoEdge);
  }
  return out;
}

}  // namespace

RingEndSet assignRingEnds(const cv::Mat& mask, const std::vector<std::int32_t>& labels,
                          const std::vector<RingEnd>& ends, const std::vector<Eigen::Vector2f>& pixels,
                          const RingEndRules& rules) {
  RingEndSet out;
  if (ends.empty() || mask.empty() || labels.size() != pixels.size()) return out;
  // The components are found in the box of the person pixels only (they are all inside it), a
  // fraction of the image: this runs for every pair each time a fit reads the rings' ends.
  const cv::Rect box = cv::boundingRect(mask);
  if (box.empty()) return out;
  cv::Mat crop, stats, centroids;
  cv::connectedComponentsWithStats(mask(box) != 0, crop, stats, centroids, 8, CV_32S);
  cv::Mat regions = cv::Mat::zeros(mask.size(), CV_32S);
  crop.copyTo(regions(box));
  stats.col(cv::CC_STAT_LEFT) += box.x;
  stats.col(cv::CC_STAT_TOP) += box.y;
  const std::map<std::int32_t, int> owner = ownRegions(regions, labels, pixels, rules.min_inside);
  std::map<int, std::uint32_t> outline_of;  // region -> index into out.outlines
  std::size_t previous = ends.size();        // index into `ends` of the last end kept
  for (std::size_t k = 0; k < ends.size(); ++k) {
    const RingEnd& e = ends[k];
    if (e.point >= pixels.size() || e.neighbour >= pixels.size()) continue;
    const auto own = owner.find(labels[e.point]);
    if (own == owner.end() || own->second == 0) continue;
    const Eigen::Vector2f& p = pixels[e.point];
    const Eigen::Vector2f& n = pixels[e.neighbour];
    if (!p.allFinite() || !n.allFinite() || p.x() == n.x()) continue;
    auto known = outline_of.find(own->second);
    if (known == outline_of.end()) {
      const int k = own->second;
      const cv::Rect box(stats.at<int>(k, cv::CC_STAT_LEFT), stats.at<int>(k, cv::CC_STAT_TOP),
                         stats.at<int>(k, cv::CC_STAT_WIDTH), stats.at<int>(k, cv::CC_STAT_HEIGHT));
      out.outlines.push_back(outlineOf(regions, k, box, rules.clearance_px));
      known = outline_of.emplace(own->second, static_cast<std::uint32_t>(out.outlines.size() - 1)).first;
    }
    const int side = p.x() > n.x() ? 1 : -1;
    // findRingEnds gives each ring's two ends one after the other.
    const bool pairs = k % 2 == 1 && previous == k - 1 && out.ends.back().outline == known->second &&
                       out.ends.back().side != side;
    out.ends.push_back({e.point, side, known->second, 0.5f * (p - n).norm(), pairs});
    previous = k;
  }
  return out;
}

float ringEndCost(const PersonOutline& outline, int side, float u, float v, float half_step, float cap) {
  const std::vector<float>& edge = side > 0 ? outline.right : outline.left;
  return ringEndCost(edge.data(), static_cast<int>(edge.size()), outline.first_row, side, u, v, half_step, cap);
}

}  // namespace thermal_lidar_calibration
