#include "thermal_lidar_calibration/core/person_counter.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
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
template <typename T>
int distinctNonZero(const cv::Mat& mask, int& single_value) {
  std::vector<bool> seen(static_cast<std::size_t>(1) << (8 * sizeof(T)), false);
  int distinct = 0;
  for (int r = 0; r < mask.rows; ++r) {
    const T* row = mask.ptr<T>(r);
    for (int c = 0; c < mask.cols; ++c) {
      const T v = row[c];
      if (v != 0 && !seen[v]) {
        seen[v] = true;
        ++distinct;
        single_value = v;
      }
    }
  }
  return distinct;
}

}  // namespace

int countMaskPeople(const cv::Mat& mask) {
  requireMaskType(mask, "countMaskPeople");
  if (mask.empty()) return 0;
  int single_value = 0;
  const int distinct = mask.depth() == CV_8U ? distinctNonZero<std::uint8_t>(mask, single_value)
                                             : distinctNonZero<std::uint16_t>(mask, single_value);
  if (distinct != 1) return distinct;
  // One shared value: a binary mask; people are its 8-connected components.
  cv::Mat binary = mask != 0;  // CV_8UC1, 255 on person pixels
  cv::Mat components;
  const int labels = cv::connectedComponents(binary, components, 8, CV_32S);
  return labels - 1;  // label 0 is the background
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
