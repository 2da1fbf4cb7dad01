#pragma once
// Counting people in each modality.

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include <cstdint>
#include <limits>
#include <map>
#include <vector>

namespace thermal_lidar_calibration {

// People in a mask (CV_8UC1 or CV_16UC1): the number of distinct non-zero ids; if all non-zero
// pixels share one value, the number of 8-connected components of the non-zero pixels.
int countMaskPeople(const cv::Mat& mask);

// The person regions of a mask, numbered as countMaskPeople counts them: distinct non-zero ids
// are regions; a mask whose non-zero pixels share one value has its 8-connected components as
// regions. CV_16UC1, 0 background, 1..n; n in `count` when given. Throws std::invalid_argument on
// a mask that is not CV_8UC1 / CV_16UC1 or has more than 65535 regions.
cv::Mat personRegions(const cv::Mat& mask, int* count = nullptr);

// Binary mask (CV_8UC1, 1 = person) from an id mask.
cv::Mat binarizeMask(const cv::Mat& mask);

// Points per distinct label.
std::map<std::int32_t, int> clusterSizes(const std::vector<std::int32_t>& labels);

// What the frame gate decides on: people in the mask, people (distinct labels) in the clusters
// and the size of the smallest cluster (max() when there is none).
struct PeopleCounts {
  int mask_people = 0;
  int cluster_people = 0;
  int smallest_cluster_points = std::numeric_limits<int>::max();
};
// The one way people are counted, by the ingest path and by anything that predicts it (the
// synthetic rig): countMaskPeople on the mask, clusterSizes on the labels.
PeopleCounts countPeople(const cv::Mat& mask, const std::vector<std::int32_t>& labels);

}  // namespace thermal_lidar_calibration
