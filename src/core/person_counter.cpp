#include "thermal_lidar_calibration/core/person_counter.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>

namespace thermal_lidar_calibration {

namespace {

void requireMaskType(const cv::Mat& mask, const char* who) {
  if (mask.type() != CV_8UC1 && mask.type() != CV_16UC1) {
    throw std::invalid_argument(std::string(who) + ": the person mask must be CV_8UC1 or " +
                                "CV_16UC1 (mono8/8UC1/mono16/16UC1), got OpenCV type " +
                                cv::typeToString(mask.type()));
  }
}

// Number of distinct non-zero values; `single_value` is set to the value when there is one.
// Every frame's mask passes here (the count rule, the association), and most of a mask is
// background: eight bytes of zeros are skipped at once (5 % of a default calibrate_bag run went
// to this loop pixel by pixel).
template <typename T>
int distinctNonZero(const cv::Mat& mask, int& single_value) {
  constexpr int kPerWord = static_cast<int>(sizeof(std::uint64_t) / sizeof(T));
  std::vector<std::uint8_t> seen(static_cast<std::size_t>(1) << (8 * sizeof(T)), 0);
  int distinct = 0;
  for (int r = 0; r < mask.rows; ++r) {
    const T* row = mask.ptr<T>(r);
    int c = 0;
    while (c < mask.cols) {
      if (c + kPerWord <= mask.cols) {
        std::uint64_t word;
        std::memcpy(&word, row + c, sizeof(word));
        if (word == 0) {
          c += kPerWord;
          continue;
        }
      }
      const int end = std::min(mask.cols, c + kPerWord);
      for (; c < end; ++c) {
        const T v = row[c];
        if (v != 0 && !seen[v]) {
          seen[v] = 1;
          ++distinct;
          single_value = v;
        }
      }
    }
  }
  return distinct;
}

int distinctValues(const cv::Mat& mask, int& single_value) {
  return mask.depth() == CV_8U ? distinctNonZero<std::uint8_t>(mask, single_value)
                               : distinctNonZero<std::uint16_t>(mask, single_value);
}

// A mask whose person pixels share one value (a binary mask): its people are its 8-connected
// components, labelled 1..n in `components` (CV_32S); returns n.
int binaryComponents(const cv::Mat& mask, cv::Mat& components) {
  return cv::connectedComponents(mask != 0, components, 8, CV_32S) - 1;  // label 0 is the background
}

// Distinct non-zero ids as regions 1..n in increasing id order (CV_16UC1).
template <typename T>
cv::Mat regionsFromIds(const cv::Mat& mask) {
  std::vector<int> id_of(static_cast<std::size_t>(1) << (8 * sizeof(T)), 0);
  for (int r = 0; r < mask.rows; ++r) {
    const T* row = mask.ptr<T>(r);
    for (int c = 0; c < mask.cols; ++c) id_of[row[c]] = row[c] != 0 ? 1 : 0;
  }
  int count = 0;
  for (int& id : id_of) id = id != 0 ? ++count : 0;
  cv::Mat regions(mask.size(), CV_16UC1);
  for (int r = 0; r < mask.rows; ++r) {
    const T* row = mask.ptr<T>(r);
    std::uint16_t* out = regions.ptr<std::uint16_t>(r);
    for (int c = 0; c < mask.cols; ++c) out[c] = static_cast<std::uint16_t>(id_of[row[c]]);
  }
  return regions;
}

}  // namespace

int countMaskPeople(const cv::Mat& mask) {
  requireMaskType(mask, "countMaskPeople");
  if (mask.empty()) return 0;
  int single_value = 0;
  const int distinct = distinctValues(mask, single_value);
  if (distinct != 1) return distinct;
  cv::Mat components;
  return binaryComponents(mask, components);
}

cv::Mat personRegions(const cv::Mat& mask, int* count) {
  requireMaskType(mask, "personRegions");
  int single_value = 0;
  int n = mask.empty() ? 0 : distinctValues(mask, single_value);
  cv::Mat regions;
  if (n == 1) {
    cv::Mat components;
    n = binaryComponents(mask, components);
    if (n > 65535) throw std::invalid_argument("personRegions: more than 65535 regions in the mask");
    components.convertTo(regions, CV_16U);
  } else {
    regions = mask.depth() == CV_8U ? regionsFromIds<std::uint8_t>(mask) : regionsFromIds<std::uint16_t>(mask);
  }
  if (count) *count = n;
  return regions;
}

cv::Mat binarizeMask(const cv::Mat& mask) {
  requireMaskType(mask, "binarizeMask");
  if (mask.empty()) return cv::Mat(mask.rows, mask.cols, CV_8UC1);
  cv::Mat binary = mask != 0;  // 255 / 0
  binary.setTo(1, binary);
  return binary;
}

std::map<std::int32_t, int> clusterSizes(const std::vector<std::int32_t>& labels) {
  std::map<std::int32_t, int> sizes;
  for (const std::int32_t label : labels) ++sizes[label];
  return sizes;
}

PeopleCounts countPeople(const cv::Mat& mask, const std::vector<std::int32_t>& labels) {
  PeopleCounts counts;
  counts.mask_people = countMaskPeople(mask);
  const std::map<std::int32_t, int> sizes = clusterSizes(labels);
  counts.cluster_people = static_cast<int>(sizes.size());
  for (const auto& label_size : sizes) {
    counts.smallest_cluster_points = std::min(counts.smallest_cluster_points, label_size.second);
  }
  return counts;
}

}  // namespace thermal_lidar_calibration
