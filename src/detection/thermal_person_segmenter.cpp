#include "thermal_lidar_calibration/detection/thermal_person_segmenter.hpp"

#include "cold_band_join.hpp"
#include "opened_parts.hpp"
#include "thermal_regions.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <string>

namespace thermal_lidar_calibration {
namespace detection {
namespace {

// Robust statistics of a sub-sampled grid of pixels: the median (background level), an upper
// percentile (the warm tail), and the pixel noise: 1.4826 * MAD of the differences between
// horizontal neighbours / sqrt(2), which scene structure (sky above ground) does not inflate as
// it does the MAD of the values. A grid of every 4th pixel (20k samples of a 640x512 frame)
// costs ~0.05 ms, a full-frame median ~1 ms.
struct FrameLevels {
  double median = 0;
  double tail = 0;
  double noise_sigma = 0;
};

template <typename T>
FrameLevels sampleLevels(const cv::Mat& image, int step, double tail_percentile) {
  std::vector<int> samples, differences;
  const auto expected = static_cast<std::size_t>((image.rows / step + 1) * (image.cols / step + 1));
  samples.reserve(expected);
  differences.reserve(expected);
  for (int y = step / 2; y < image.rows; y += step) {
    const T* row = image.ptr<T>(y);
    for (int x = step / 2; x < image.cols; x += step) {
      samples.push_back(row[x]);
      if (x + 1 < image.cols) differences.push_back(std::abs(static_cast<int>(row[x + 1]) - static_cast<int>(row[x])));
    }
  }
  const std::size_t n = samples.size();
  const std::size_t mid = n / 2;
  std::nth_element(samples.begin(), samples.begin() + mid, samples.end());
  FrameLevels levels;
  levels.median = samples[mid];
  // The upper tail lies in [mid, n): a second partial sort there only.
  const auto tail_index = std::min(
      n - 1, static_cast<std::size_t>(std::floor(tail_percentile / 100.0 * static_cast<double>(n - 1))));
  if (tail_index > mid) {
    std::nth_element(samples.begin() + mid + 1, samples.begin() + tail_index, samples.end());
  }
  levels.tail = samples[std::max(tail_index, mid)];
  if (!differences.empty()) {
    const std::size_t dmid = differences.size() / 2;
    std::nth_element(differences.begin(), differences.begin() + dmid, differences.end());
    levels.noise_sigma = 1.4826 * differences[dmid] / std::sqrt(2.0);
  }
  return levels;
}

cv::Mat squareKernel(int radius) {
  return cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * radius + 1, 2 * radius + 1));
}

// Writes `id` where labels == label inside the component's box and returns the mean pixel
// value there (raw units).
template <typename T>
double paintComponent(const cv::Mat& image, const cv::Mat& labels, int label, const cv::Rect& box,
                      std::uint8_t id, cv::Mat* mask) {
  double sum = 0;
  long count = 0;
  for (int y = box.y; y < box.y + box.height; ++y) {
    const int* lab = labels.ptr<int>(y);
    const T* pix = image.ptr<T>(y);
    std::uint8_t* out = mask->ptr<std::uint8_t>(y);
    for (int x = box.x; x < box.x + box.width; ++x) {
      if (lab[x] != label) continue;
      out[x] = id;
      sum += pix[x];
      ++count;
    }
  }
  return count > 0 ? sum / static_cast<double>(count) : 0.0;
}

// Relative mode: the regions whose warmest 1 % (kCoreQuantile) stays below min_core of the way
// from the background level to the bar (the warm tail, or the warmest region's core if lower)
// move to `rejected` as "no_warm_core".
constexpr double kCoreQuantile = 0.99;
void dropRegionsWithoutWarmCore(const cv::Mat& image, const cv::Mat& labels, const FrameLevels& levels,
                                double min_core, std::vector<WarmRegion>* kept, ThermalSegmentation* result) {
  std::vector<double> cores;
  double warmest = 0.0;
  for (const WarmRegion& region : *kept) {
    cores.push_back(regionQuantile(image, labels, region, kCoreQuantile));
    warmest = std::max(warmest, cores.back());
  }
  const double bar = std::min(levels.tail, warmest);
  result->core_threshold = levels.median + min_core * (bar - levels.median);
  std::vector<WarmRegion> warm;
  for (std::size_t i = 0; i < kept->size(); ++i) {
    const WarmRegion& region = (*kept)[i];
    if (cores[i] >= result->core_threshold) {
      warm.push_back(region);
    } else {
      result->rejected.push_back({region.bbox, region.area_px, "no_warm_core", legsOverTorso(region)});
    }
  }
  *kept = std::move(warm);
}

// A region that is no person as a whole (too squat, or without a neck: two people side by side
// whose heads touch, two riders on a scooter, the dip between their heads shallower than
// head_dip_fraction) is cut at every valley of kFailedDipScale times that dip, and the cut is
// kept only when each part of a person's size passes the person tests on its own (and at least
// two do): a warm car or wall patch whose top is merely uneven leaves a part that is no person,
// and stays one rejected region.
constexpr double kFailedDipScale = 0.5;
// The parts of a split region, marked and measured for the person tests.
std::vector<WarmRegion> measuredParts(const cv::Mat& labels, std::vector<WarmRegion> parts) {
  for (WarmRegion& part : parts) {
    part.split_part = true;
    part.zones = measureZoneWidths(labels, part);
  }
  return parts;
}
// The region cut as above (measured parts), or the region alone when the cut is not kept.
template <typename FailureOf>
std::vector<WarmRegion> splitFailedRegion(const cv::Mat& labels, const cv::Mat& opened, const WarmRegion& region,
                                          const ThermalSegmenterConfig& c, const FailureOf& failureOf) {
  std::vector<WarmRegion> parts = splitAtHeads(labels, opened, region, kFailedDipScale * c.head_dip_fraction);
  if (parts.size() <= 1) return {region};
  parts = measuredParts(labels, std::move(parts));
  int people = 0;
  for (const WarmRegion& part : parts) {
    const std::string failure = failureOf(part);
    if (failure.empty()) {
      ++people;
    } else if (failure != "too_small") {
      return {region};
    }
  }
  return people >= 2 ? parts : std::vector<WarmRegion>{region};
}

// The components of `labels` (stats and centroids as connectedComponentsWithStats gives them),
// judged one by one, split at heads where a region is wide enough to hold people side by side,
// and joined across thin cold bands (relabelling `labels`): the person regions; the others go to
// result->rejected.
std::vector<WarmRegion> judgeComponents(const ThermalSegmenterConfig& c, const cv::Size& size, cv::Mat& labels,
                                        const cv::Mat& opened, const cv::Mat& stats, const cv::Mat& centroids,
                                        ThermalSegmentation* result) {
  const int n = stats.rows;
  const RegionLimits limits = regionLimits(c, size);
  result->min_area_px = limits.min_area_px;
  result->min_height_px = limits.min_height_px;
  // A region too small, too large or too short for a person is that whether or not the border
  // cuts it (a hand split off a cut person, warm ground along the bottom edge); one of a person's
  // size that the border cuts is dropped for that, whatever else its shape says.
  const auto failureOf = [&](const WarmRegion& region) {
    const std::string shape = shapeFailure(region, c, limits);
    if (shape == "too_small" || shape == "too_large" || shape == "too_short") return shape;
    return cutByBorder(region.bbox, size, c.border_margin_px) ? std::string("cut_by_border") : shape;
  };
  const auto reject = [&](const WarmRegion& region, const std::string& reason) {
    result->rejected.push_back({region.bbox, region.area_px, reason, legsOverTorso(region)});
    if (reason == "cut_by_border") ++result->border_cut;
  };
  std::vector<WarmRegion> kept;
  std::vector<FailedRegion> failed;  // whole regions that are no person, judged once joins are tried
  for (int k = 1; k < n; ++k) {
    WarmRegion region;
    region.label = k;
    region.bbox = cv::Rect(stats.at<int>(k, cv::CC_STAT_LEFT), stats.at<int>(k, cv::CC_STAT_TOP),
                           stats.at<int>(k, cv::CC_STAT_WIDTH), stats.at<int>(k, cv::CC_STAT_HEIGHT));
    region.area_px = stats.at<int>(k, cv::CC_STAT_AREA);
    region.centroid = cv::Point2d(centroids.at<double>(k, 0), centroids.at<double>(k, 1));
    if (region.area_px < c.min_area_px) continue;  // specks: nothing to split or report
    region.zones = measureZoneWidths(labels, region);
    const std::string failure = failureOf(region);
    // A region wider than one person for its height may hold people side by side.
    const double aspect = static_cast<double>(region.bbox.height) / region.bbox.width;
    if (aspect < c.split_max_aspect && failure != "too_large" && failure != "too_short") {
      std::vector<WarmRegion> parts = splitAtHeads(labels, opened, region, c.head_dip_fraction);
      if (parts.size() > 1) {
        parts = measuredParts(labels, std::move(parts));
      } else if (!failure.empty()) {
        parts = splitFailedRegion(labels, opened, region, c, failureOf);
      }
      if (parts.size() > 1) {
        for (const WarmRegion& part : parts) {
          const std::string part_failure = failureOf(part);
          if (part_failure.empty()) {
            kept.push_back(part);
          } else if (part_failure != "too_small") {
            reject(part, part_failure);
          }
        }
        continue;
      }
    }
    if (failure.empty()) {
      kept.push_back(region);
    } else {
      failed.push_back({region, failure});
    }
  }
  joinAcrossColdBands(labels, failureOf, &kept, &failed);
  for (const FailedRegion& f : failed) reject(f.region, f.reason);
  return kept;
}
}  // namespace

ThermalPersonSegmenter::ThermalPersonSegmenter(const ThermalSegmenterConfig& config) : config_(config) {
  config_.validate();
  if (config_.open_radius_px > 0) open_kernel_ = squareKernel(config_.open_radius_px);
  if (config_.close_radius_px > 0) close_kernel_ = squareKernel(config_.close_radius_px);
}

ThermalSegmentation ThermalPersonSegmenter::segment(const cv::Mat& image) const {
  if (image.empty()) throw std::invalid_argument("thermal image is empty");
  const bool is16 = image.type() == CV_16UC1;
  if (!is16 && image.type() != CV_8UC1) {
    throw std::invalid_argument("thermal image must be 8- or 16-bit single-channel (got OpenCV type " +
                                std::to_string(image.type()) + ")");
  }
  const ThermalSegmenterConfig& c = config_;
  ThermalSegmentation result;
  result.radiometric = is16 && c.scale == ThermalScale::kAuto && c.kelvin_per_count > 0.0;
  const double full_scale = is16 ? 65535.0 : 255.0;
  const FrameLevels levels = is16 ? sampleLevels<std::uint16_t>(image, c.background_step_px, c.relative_tail_percentile)
                                  : sampleLevels<std::uint8_t>(image, c.background_step_px, c.relative_tail_percentile);

  // The person band [lo, hi] in raw counts: one inRange pass gives the 8-bit binary mask.
  double lo = 0, hi = full_scale;
  if (result.radiometric) {
    const double kpc = c.kelvin_per_count;
    const double background_k = levels.median * kpc + c.kelvin_offset;
    const double low_k = std::max(c.body_min_k, background_k + c.min_contrast_k);
    lo = std::ceil((low_k - c.kelvin_offset) / kpc);
    hi = std::floor((c.body_max_k - c.kelvin_offset) / kpc);
    result.background_level = background_k;
    result.threshold_low = low_k;
    result.threshold_high = c.body_max_k;
  } else {
    const double contrast = std::max({c.relative_threshold * (levels.tail - levels.median),
                                      c.relative_min_contrast_noise * levels.noise_sigma, 1.0});
    lo = std::ceil(levels.median + contrast);
    result.background_level = levels.median;
    result.threshold_low = lo;
    result.threshold_high = hi;
  }
  result.mask = cv::Mat::zeros(image.size(), CV_8UC1);
  lo = std::max(lo, 0.0);
  hi = std::min(hi, full_scale);
  if (lo > hi) return result;  // the scene is warmer than the body band: nobody to find

  cv::Mat warm;    // the band's pixels before the opening: what the kept people grow back into
  cv::Mat opened;  // kept as it is: the head split reads its top profile here (thermal_regions.hpp)
  cv::inRange(image, cv::Scalar(lo), cv::Scalar(hi), warm);
  if (open_kernel_.empty()) {
    opened = warm;
  } else {
    cv::morphologyEx(warm, opened, cv::MORPH_OPEN, open_kernel_);
  }
  cv::Mat binary;  // the closing writes a buffer of its own
  if (close_kernel_.empty()) {
    binary = opened;
  } else {
    cv::morphologyEx(opened, binary, cv::MORPH_CLOSE, close_kernel_);
  }

  cv::Mat labels, stats, centroids;
  // BBDT explicitly: with statistics, OpenCV 4.6's default (Spaghetti) takes ~2.2 ms on a
  // 640x512 mask, BBDT ~0.6 ms (bench/detection_benchmark.cpp measures the whole call).
  const int n = cv::connectedComponentsWithStats(binary, labels, stats, centroids, 8, CV_32S, cv::CCL_BBDT);
  result.components = n - 1;
  std::vector<WarmRegion> kept = judgeComponents(c, image.size(), labels, opened, stats, centroids, &result);
  if (!result.radiometric && c.relative_min_core > 0.0 && !kept.empty()) {
    dropRegionsWithoutWarmCore(image, labels, levels, c.relative_min_core, &kept, &result);
  }
  // Ids left to right (then top to bottom), at most 255 in an 8-bit mask.
  std::sort(kept.begin(), kept.end(), [](const WarmRegion& a, const WarmRegion& b) {
    return a.centroid.x != b.centroid.x ? a.centroid.x < b.centroid.x : a.centroid.y < b.centroid.y;
  });
  if (kept.size() > 255) kept.resize(255);
  const bool restore = !open_kernel_.empty() && c.restore_px > 0;  // else nothing was removed
  std::vector<double> floors;  // each person's coolest warm pixels (the closing's fill left out)
  for (std::size_t i = 0; i < kept.size(); ++i) {
    const WarmRegion& region = kept[i];
    ThermalPerson person;
    person.id = static_cast<int>(i) + 1;
    person.bbox = region.bbox;
    person.area_px = region.area_px;
    person.centroid = region.centroid;
    person.fill = static_cast<double>(person.area_px) / person.bbox.area();
    person.leg_to_torso_width = legsOverTorso(region);
    const auto id = static_cast<std::uint8_t>(person.id);
    // The box of a part covers only its columns, so painting the label inside it paints the part.
    const double mean = is16 ? paintComponent<std::uint16_t>(image, labels, region.label, region.bbox, id, &result.mask)
                             : paintComponent<std::uint8_t>(image, labels, region.label, region.bbox, id, &result.mask);
    person.mean_level = result.radiometric ? mean * c.kelvin_per_count + c.kelvin_offset : mean;
    result.people.push_back(person);
    if (restore) floors.push_back(regionQuantile(image, labels, region, kCoolestQuantile, warm));
  }
  if (restore) restoreOpenedParts(image, warm, binary, c.restore_px, floors, &result.mask, &result.people);
  return result;
}

}  // namespace detection
}  // namespace thermal_lidar_calibration
