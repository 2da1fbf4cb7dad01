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
// A ring whose two ends are both measured is charged as its middle and its width (ringPairCost):
// a segmentation that erodes or dilates a person moves both ends out or in by the same amount,
// which leaves the middle where it was.

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
  // The end before it in RingEndSet::ends is the other end of the same ring, on the same outline.
  bool pairs_previous = false;
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

// The signed form: s + half_step, NaN where neither row has an outline or the end is not on
// the outline's rows. ringEndCost is min(|offset|, cap), cap for NaN.
inline float ringEndOffset(const float* edge, int rows, int first_row, int side, float u, float v, float half_step) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float f = v - static_cast<float>(first_row);
  if (!(f >= -1.0f) || !(u == u) || !(f < static_cast<float>(rows))) return nan;
  const int r = static_cast<int>(std::floor(f));
  const float a = f - static_cast<float>(r);
  const float e0 = r >= 0 ? edge[r] : nan;
  const float e1 = r + 1 < rows ? edge[r + 1] : nan;
  float column;
  if (std::isfinite(e0) && std::isfinite(e1)) {
    column = e0 + a * (e1 - e0);
  } else if (std::isfinite(e0) || std::isfinite(e1)) {
    column = std::isfinite(e0) ? e0 : e1;
  } else {
    return nan;
  }
  const float beyond = static_cast<float>(side) * (u - column);
  return beyond + half_step;
}

// A lone end's charge from its ringEndOffset: |offset|, at most `cap`; `cap` when not measured.
inline float ringEndCharge(float offset, float cap) {
  return offset == offset ? std::min(std::fabs(offset), cap) : cap;
}

// The same on one side's columns (`edge[k]` for row first_row + k, `rows` of them).
inline float ringEndCost(const float* edge, int rows, int first_row, int side, float u, float v, float half_step,
                         float cap) {
  return ringEndCharge(ringEndOffset(edge, rows, first_row, side, u, v, half_step), cap);
}

// One ring's two ends, both measured (ringEndOffset a and b, either side first): how far its middle
// lies off, |a - b| (a shift along the row moves one end out and the other in), plus
// width_weight times how far its width is off, |a + b| (an eroded or dilated mask, a nearer or
// farther person), each at most `cap`. Charged end by end instead, |a| + |b| = max(|a - b|, |a + b|):
// a mask eroded or dilated by k pixels leaves the middle free over +-k, and the realistic drives'
// masks (0-2 px either way) left the roll and the yaw to their mask loss. The width is weighed
// less because every segmentation's edge moves it (at 0 and at 1 instead of 0.5 the realistic
// timing drives' roll scattered more: docs/validation/accuracy.md).
inline float ringPairCost(float a, float b, float cap, float width_weight) {
  return std::min(std::fabs(a - b), cap) + width_weight * std::min(std::fabs(a + b), cap);
}

}  // namespace thermal_lidar_calibration
