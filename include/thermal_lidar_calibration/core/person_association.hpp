#pragma once
// Pairing person by person once an extrinsic is known (issue 23, beyond the paper). The paper
// keeps a frame only when both modalities count the same people; with an extrinsic, "which cluster
// is which mask region" has an answer: project each LiDAR person cluster and see which region it
// lands on. The match is one to one and must win by a margin both ways: a cluster between two
// regions, or two clusters on one region, is left out. An unmatched region stays in the mask (the
// Eq. 3 loss measures LiDAR points against person pixels, so an extra region costs nothing); an
// unmatched cluster is dropped from the pair. ROS-free.

#include "thermal_lidar_calibration/core/calibration_pair.hpp"
#include "thermal_lidar_calibration/core/camera_model.hpp"
#include "thermal_lidar_calibration/core/extrinsic.hpp"
#include "thermal_lidar_calibration/core/parameter_range.hpp"
#include "thermal_lidar_calibration/core/person_counter.hpp"  // personRegions

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include <cstdint>
#include <optional>
#include <vector>

namespace thermal_lidar_calibration {

struct AssociationConfig {
  // A cluster's share of its in-view points that must land on (or within tolerance_px of) its
  // region.
  double min_overlap = 0.6;
  // The best share must beat the second best by this much, for the cluster (another region) and
  // for the region (another cluster).
  double margin = 0.4;
  // A projected point this close to a region's pixel counts as on it (a first fit is seldom better
  // than a pixel or two; a person's outline in the mask is not sharper).
  double tolerance_px = 3.0;
  // A cluster with fewer points in front of the camera and inside the image is left out (the
  // frame gate's min_points_per_cluster); so is one with less than half its points in view.
  int min_points_in_view = 3;
  // Associate, refit, associate again until the pairs no longer change, at most this often.
  int max_rounds = 4;
  static const ParameterRanges<AssociationConfig>& ranges();  // checked by validate()
  void validate() const;  // throws std::invalid_argument naming the key and range
};

struct ClusterMatch {
  std::int32_t label = 0;  // the LiDAR cluster's label
  int region = 0;          // its region, 1..n
  double overlap = 0.0;    // share of the cluster's in-view points on the region
  double second = 0.0;     // the best share on any other region
};

struct FrameAssociation {
  std::vector<ClusterMatch> matches;  // one to one, by increasing label
  int clusters = 0;                   // clusters in the frame
  int regions = 0;                    // regions in the mask
};

// Matches the clusters (points with one label per person, in the camera's frame already moved
// to the image's instant as the caller wants) to the regions at `extrinsic`.
FrameAssociation associateClusters(const CameraModel& camera, const cv::Mat& regions,
                                   const std::vector<Eigen::Vector3f>& points,
                                   const std::vector<std::int32_t>& labels, const Extrinsic& extrinsic,
                                   const AssociationConfig& config);

// A candidate frame (a CalibrationPair with `regions` set) associated at the extrinsic and time
// offset: with an offset its points at the image's instant (person_timing.hpp) are matched,
// without one the points as captured (the loss does the same).
FrameAssociation associateFrame(const CameraModel& camera, const CalibrationPair& frame,
                                const Extrinsic& extrinsic, std::optional<double> time_offset_s,
                                const AssociationConfig& config);

// The pair an association makes of a candidate frame: only the matched clusters' points (with
// their times, velocities and motion), the whole mask as person pixels, rule kAssociation.
// nullopt when nothing matched.
std::optional<CalibrationPair> associatedPair(const CalibrationPair& frame, const FrameAssociation& association);

}  // namespace thermal_lidar_calibration
