#pragma once
// Beyond the paper (issue 24): where each LiDAR ring leaves a person, against that person's own
// mask region. A mask loss charges only points outside the masks, so it is lowest where the
// projected people are smaller: a segmentation that erodes a person's mask pulls the fit that way
// and one that dilates it does not push back (the realistic drives lean forward along camera z).
// A ring's first and last point on a person lie on the person's outline, on average half an
// azimuth step inside it, so they tell the fit both ways. Measured against the union of all
// people's pixels (what a pair's mask holds) the ends lie 2.6-5.7 px inside on average (people
// side by side, people the mask did not report); against each person's own region, +0.1 px. So
// each cluster's ends are measured against the region its points fall in, along the image row (a
// ring crosses a person sideways; the nearest outline of a top ring's end may be a head's top),
// and ends whose outline borders another region or the image border are left out.

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace thermal_lidar_calibration {

struct RingEnd {
  std::uint32_t point;      // the ring's first or last point on the person
  std::uint32_t neighbour;  // the next point inward on the same ring
};

// Points (LiDAR frame, the sensor's own: rings are cones of one elevation) grouped by label and
// ring, a ring being a run of points whose elevations differ by less than `ring_gap_rad` from
// the next; for every ring with at least `min_points` points on a label, its two ends by azimuth,
// in that order; a run spread over more than 0.05 deg of elevation is no ring. A label whose runs
// cover more than 5 % of its elevation span (and more than `ring_gap_rad`), or whose rings hold
// less than half its points, has none: its points are not on scan lines.
// Labels <= 0 (no person) are left out; without one label per point nothing is returned.
std::vector<RingEnd> findRingEnds(const std::vector<Eigen::Vector3f>& points,
                                  const std::vector<std::int32_t>& labels,
                                  double ring_gap_rad = 0.1 * 3.14159265358979 / 180.0, int min_points = 3);

// A person's outline in the image, row by row: on each side, the column of the outline (pixel
// centres at integers; the outline half a pixel beyond the outermost person pixel of the row);
// NaN where the row has no pixel of the person, or beyond the outline lies the image border or
// another person's region within RingEndRules::clearance_px.
struct PersonOutline {
  int first_row = 0;
  std::vector<float> left, right;
};

// A ring end with the outline it belongs to.
struct AssignedRingEnd {
  std::uint32_t point = 0;
  int side = 0;               // +1: the ring's rightmost point on the person in the image, -1: leftmost
  std::uint32_t outline = 0;  // index into RingEndSet::outlines
  // Half the pixels from the end to the next point inward at assignment, where the end lies
  // inside the outline on average (a fit moves it by far less than the spacing changes).
  float half_step = 0.0f;
};

struct RingEndSet {
  std::vector<PersonOutline> outlines;
  std::vector<AssignedRingEnd> ends;
};

struct RingEndRules {
  int clearance_px = 3;      // an outline within this many pixels of another region is left out
  double min_inside = 0.5;   // a cluster owns the region holding at least this fraction of its points
};

// The ends of `ends` whose cluster (by `labels`) owns one region of `mask` (8-connected person
// pixels, CV_8UC1 non-zero): most of the cluster's projected points (`pixels`, one per point,
// NaN when behind the camera) fall in it, at least rules.min_inside of them, and no other cluster
// owns it; with the outlines of those regions. An end's side is where it projects against its
// neighbour. A ring's ends are its outermost points on a person, so they are measured against the
// outermost person pixels of their row whatever the pose was (only the ownership depends on it).
RingEndSet assignRingEnds(const cv::Mat& mask, const std::vector<std::int32_t>& labels,
                          const std::vector<RingEnd>& ends, const std::vector<Eigen::Vector2f>& pixels,
                          const RingEndRules& rules = {});

// An end on `side` of `outline` at pixel (u, v): |s + half_step|, at most `cap`; s its signed
// distance beyond the outline along the row (the outline's column interpolated between the two
// rows around v, one row's alone where the other has none; positive outside). Where neither row
// has an outline: `cap`.
float ringEndCost(const PersonOutline& outline, int side, float u, float v, float half_step, float cap);

// The same on one side's columns (`edge[k]` for row first_row + k, `rows` of them): what the
// loss kernels inline.
inline float ringEndCost(const float* edge, int rows, int first_row, int side, float u, float v, float half_step,
                         float cap) {
  const float f = v - static_cast<float>(first_row);
  if (!(f >= -1.0f) || !(u == u) || !(f < static_cast<float>(rows))) return cap;
  const int r = static_cast<int>(std::floor(f));
  const float a = f - static_cast<float>(r);
  const float e0 = r >= 0 ? edge[r] : std::numeric_limits<float>::quiet_NaN();
  const float e1 = r + 1 < rows ? edge[r + 1] : std::numeric_limits<float>::quiet_NaN();
  float column;
  if (std::isfinite(e0) && std::isfinite(e1)) {
    column = e0 + a * (e1 - e0);
  } else if (std::isfinite(e0) || std::isfinite(e1)) {
    column = std::isfinite(e0) ? e0 : e1;
  } else {
    return cap;
  }
  const float beyond = static_cast<float>(side) * (u - column);
  return std::min(std::fabs(beyond + half_step), cap);
}

}  // namespace thermal_lidar_calibration
