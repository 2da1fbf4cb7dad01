#include "cold_band_join.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>

namespace thermal_lidar_calibration {
namespace detection {
namespace {

// A thin band: LLVIP's cold belts are 10-30 px high on people ~250 px tall (0.04-0.12).
constexpr double kMaxColdBandFraction = 0.15;
// The columns [first, last] that `label` covers in rows [y0, y1) of `box` (first > last: none).
std::pair<int, int> columnSpan(const cv::Mat& labels, int label, const cv::Rect& box, int y0, int y1) {
  int first = box.x + box.width, last = box.x - 1;
  for (int y = std::max(y0, box.y); y < std::min(y1, box.y + box.height); ++y) {
    const int* row = labels.ptr<int>(y);
    for (int x = box.x; x < box.x + box.width; ++x) {
      if (row[x] != label) continue;
      first = std::min(first, x);
      last = std::max(last, x);
    }
  }
  return {first, last};
}
// The body goes on across the band: the columns the upper region covers in its lowest
// kBandEdgeFraction of the joined height and those the lower one covers in its highest share at
// least half of the wider of the two (a waist above hips). A person's feet above a warm bollard
// or a drain do not: the stride spans more than twice the bollard's top.
constexpr double kBandEdgeFraction = 0.05;
bool joinable(const cv::Mat& labels, const WarmRegion& upper, const WarmRegion& lower) {
  const cv::Rect& u = upper.bbox;
  const cv::Rect& l = lower.bbox;
  const int overlap = std::min(u.x + u.width, l.x + l.width) - std::max(u.x, l.x);
  const int gap = l.y - (u.y + u.height);
  const int joined_height = std::max(u.y + u.height, l.y + l.height) - u.y;
  if (overlap < 0.5 * std::min(u.width, l.width) || gap < 0 || gap > kMaxColdBandFraction * joined_height) {
    return false;
  }
  const int edge = std::max(2, static_cast<int>(std::lround(kBandEdgeFraction * joined_height)));
  const auto above = columnSpan(labels, upper.label, u, u.y + u.height - edge, u.y + u.height);
  const auto below = columnSpan(labels, lower.label, l, l.y, l.y + edge);
  const int shared = std::min(above.second, below.second) - std::max(above.first, below.first) + 1;
  const int wider = std::max(above.second - above.first, below.second - below.first) + 1;
  return shared >= 0.5 * wider;
}
WarmRegion joined(const WarmRegion& upper, const WarmRegion& lower) {
  WarmRegion both = upper;
  both.bbox = upper.bbox | lower.bbox;
  both.area_px = upper.area_px + lower.area_px;
  both.centroid = (upper.centroid * upper.area_px + lower.centroid * lower.area_px) / both.area_px;
  return both;
}
void relabel(cv::Mat& labels, const cv::Rect& box, int from, int to) {
  for (int y = box.y; y < box.y + box.height; ++y) {
    int* row = labels.ptr<int>(y);
    for (int x = box.x; x < box.x + box.width; ++x) {
      if (row[x] == from) row[x] = to;
    }
  }
}
}  // namespace

void joinAcrossColdBands(cv::Mat& labels, const std::function<std::string(const WarmRegion&)>& failureOf,
                         std::vector<WarmRegion>* kept, std::vector<FailedRegion>* failed) {
  for (std::size_t i = 0; i < failed->size();) {
    const FailedRegion& lower = (*failed)[i];
    bool done = false;
    if (lower.reason != "too_large" && lower.reason != "cut_by_border") {
      // The candidates above: people (whole regions, not parts of a split one) and other failures,
      // as (in kept, index).
      std::vector<std::pair<bool, std::size_t>> uppers;
      for (std::size_t k = 0; k < kept->size(); ++k) {
        if (!(*kept)[k].split_part) uppers.emplace_back(true, k);
      }
      for (std::size_t j = 0; j < failed->size(); ++j) {
        if (j != i) uppers.emplace_back(false, j);
      }
      for (const auto& [in_kept, j] : uppers) {
        WarmRegion& upper = in_kept ? (*kept)[j] : (*failed)[j].region;
        if (!joinable(labels, upper, lower.region)) continue;
        // The lower region starts below the upper one's last row: its box holds no upper pixel.
        relabel(labels, lower.region.bbox, lower.region.label, upper.label);
        WarmRegion both = joined(upper, lower.region);
        both.zones = measureZoneWidths(labels, both);
        if (!failureOf(both).empty()) {
          relabel(labels, lower.region.bbox, upper.label, lower.region.label);
          continue;
        }
        if (in_kept) {
          upper = both;
          failed->erase(failed->begin() + static_cast<std::ptrdiff_t>(i));
        } else {
          kept->push_back(both);
          // Erase the higher index first so the lower one stays valid.
          failed->erase(failed->begin() + static_cast<std::ptrdiff_t>(std::max(i, j)));
          failed->erase(failed->begin() + static_cast<std::ptrdiff_t>(std::min(i, j)));
        }
        done = true;
        break;
      }
    }
    i = done ? 0 : i + 1;  // a joined region may take a third part below it
  }
}

}  // namespace detection
}  // namespace thermal_lidar_calibration
