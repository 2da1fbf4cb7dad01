#include "thermal_lidar_calibration/detection/person_size_model.hpp"

#include <opencv2/core.hpp>

#include <algorithm>
#include <cmath>

namespace thermal_lidar_calibration {
namespace detection {
namespace {

// People of one drive look within about +-20 % of the model's height at a given foot row
// (walking, clothing, the terrain rolling under the horizon; on the synthetic drives 90 % of the
// people are within 0.85-1.19): a window of 1.45x in height holds the people's band.
const double kBandLog = std::log(1.45);
constexpr int kRefitEveryFrames = 5;     // a refit costs ~1 ms at 300 samples
constexpr int kHorizonCandidates = 240;  // horizon rows tried per refit
constexpr double kMinFootGapPx = 4.0;    // feet this close to the horizon are not judged
// The horizon lies at most this many median heights above the lowest feet (a camera ~10 m
// high looking at 1.75 m people: ~6).
constexpr double kMaxHorizonHeights = 10.0;

double median(std::vector<double> v) {
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

}  // namespace

PersonSizeModel::PersonSizeModel(const ThermalSegmenterConfig& config)
    : history_(config.size_history), min_samples_(config.size_min_samples), min_ratio_(config.size_min_ratio) {}

void PersonSizeModel::observe(const std::vector<cv::Rect>& boxes) {
  if (history_ <= 0) return;
  for (const cv::Rect& b : boxes) {
    samples_.emplace_back(static_cast<float>(b.y + b.height), static_cast<float>(b.height));
    if (static_cast<int>(samples_.size()) > history_) samples_.pop_front();
  }
  if (++frames_since_fit_ >= kRefitEveryFrames) {
    frames_since_fit_ = 0;
    refit();
  }
}

// For each candidate horizon row, the candidates' log(height / (foot - horizon)) are sorted and
// the densest window of kBandLog found; the horizon whose window holds the most candidates wins
// (the first on ties: deterministic). People are the biggest such band; animals end on form a
// smaller, lower one, and the model never flags what is taller than its band.
void PersonSizeModel::refit() {
  fit_.reset();
  const int n = static_cast<int>(samples_.size());
  if (n < min_samples_) return;
  std::vector<double> feet, heights;
  for (const cv::Point2f& s : samples_) {
    feet.push_back(s.x);
    heights.push_back(s.y);
  }
  // Horizons from just above the highest feet (but for the highest 5 %: a stray warm spot high
  // in the image must not rule out the true horizon) upwards.
  std::vector<double> sorted_feet = feet;
  std::sort(sorted_feet.begin(), sorted_feet.end());
  const double highest_feet = sorted_feet[sorted_feet.size() / 20];
  const double median_height = median(heights);
  const double span = kMaxHorizonHeights * median_height;
  const double step = span / kHorizonCandidates;
  std::vector<double> log_ratio;
  log_ratio.reserve(samples_.size());
  PersonSizeFit best;
  double best_centre = 0;
  for (int c = 0; c <= kHorizonCandidates; ++c) {
    const double horizon = highest_feet - kMinFootGapPx - c * step;
    log_ratio.clear();
    for (int i = 0; i < n; ++i) {
      if (feet[i] - horizon >= kMinFootGapPx) log_ratio.push_back(std::log(heights[i] / (feet[i] - horizon)));
    }
    std::sort(log_ratio.begin(), log_ratio.end());
    const int m = static_cast<int>(log_ratio.size());
    int count = 0;
    double centre = 0;
    for (int lo = 0, hi = 0; lo < m; ++lo) {
      while (hi < m && log_ratio[hi] - log_ratio[lo] <= kBandLog) ++hi;
      if (hi - lo > count) {
        count = hi - lo;
        centre = log_ratio[lo + (hi - lo) / 2];
      }
    }
    if (count > best.support) {
      best.support = count;
      best.horizon_row = horizon;
      best_centre = centre;
    }
  }
  best.samples = n;
  best.slope = std::exp(best_centre);
  // Ready only with a clear band (most candidates in it) spread over enough distances to place
  // the horizon: feet of the band's candidates spanning at least half a median height.
  if (2 * best.support < n) return;
  std::vector<double> band_feet;
  for (int i = 0; i < n; ++i) {
    if (feet[i] - best.horizon_row < kMinFootGapPx) continue;
    const double r = std::log(heights[i] / (feet[i] - best.horizon_row));
    if (std::abs(r - best_centre) <= kBandLog / 2) band_feet.push_back(feet[i]);
  }
  if (band_feet.empty()) return;
  std::sort(band_feet.begin(), band_feet.end());
  const double spread = band_feet[band_feet.size() * 9 / 10] - band_feet[band_feet.size() / 10];
  if (spread < 0.5 * median_height) return;
  fit_ = best;
}

std::optional<double> PersonSizeModel::heightRatio(const cv::Rect& box) const {
  if (!fit_) return std::nullopt;
  const double gap = box.y + box.height - fit_->horizon_row;
  if (gap < kMinFootGapPx) return std::nullopt;
  return box.height / (fit_->slope * gap);
}

bool PersonSizeModel::tooShortForItsRange(const cv::Rect& box) const {
  const std::optional<double> r = heightRatio(box);
  return r && *r < min_ratio_;
}

void applySizeCheck(ThermalSegmentation& segmentation, PersonSizeModel& model) {
  std::vector<cv::Rect> boxes;
  std::vector<ThermalPerson> kept;
  cv::Mat lut(1, 256, CV_8U, cv::Scalar(0));
  for (const ThermalPerson& p : segmentation.people) {
    boxes.push_back(p.bbox);
    if (model.tooShortForItsRange(p.bbox)) {
      segmentation.rejected.push_back({p.bbox, p.area_px, "too_short_for_range", p.leg_to_torso_width});
      continue;
    }
    kept.push_back(p);
    kept.back().id = static_cast<int>(kept.size());
    lut.at<std::uint8_t>(p.id) = static_cast<std::uint8_t>(kept.back().id);
  }
  if (kept.size() != segmentation.people.size()) {
    cv::LUT(segmentation.mask, lut, segmentation.mask);
    segmentation.people = std::move(kept);
  }
  model.observe(boxes);
}

}  // namespace detection
}  // namespace thermal_lidar_calibration
