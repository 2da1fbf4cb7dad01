#pragma once
// One kept (person mask, LiDAR person points) pair: what the gate keeps and the optimizer uses.

#include "thermal_lidar_calibration/core/person_motion.hpp"

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace thermal_lidar_calibration {

class DistanceMap;

// A decoded synchronized frame as it arrives from a bag or topics (before gating).
struct Frame {
  double stamp_s = 0.0;           // stamp of the image, seconds
  std::string camera_frame;       // frame_id of the image
  std::string lidar_frame;        // frame_id of the clusters
  cv::Mat image;                  // thermal image, CV_8UC1 or CV_16UC1 (may be empty)
  cv::Mat mask;                   // person mask, CV_8UC1 or CV_16UC1, 0 = background
  std::vector<Eigen::Vector3f> points;  // finite cluster points, LiDAR frame, metres
  std::vector<std::int32_t> labels;     // one label per point: one label per person
  std::size_t nonfinite_points_dropped = 0;  // NaN/inf points removed while decoding
  double cloud_stamp_s = 0.0;           // stamp of the clusters (the image's may differ)
  std::vector<float> point_time_s;      // per point, relative to cloud_stamp_s; empty: none
  // Per point, relative to the LiDAR (m/s), when the source already measured it (a dataset bag
  // written by the node); empty otherwise.
  std::vector<Eigen::Vector3f> point_velocity;
  std::vector<PersonMotion> motion;  // and its people's motion, when the source says it
};

// Which rule made a pair (issue 23): the paper's equal counts, or person-by-person association
// with a known extrinsic (person_association.hpp).
enum class PairRule : std::uint8_t { kCounts, kAssociation };

// A pair in the dataset D of the paper.
struct CalibrationPair {
  double stamp_s = 0.0;
  cv::Mat mask;    // CV_8UC1, 1 on person pixels, 0 elsewhere (I^h of the paper)
  cv::Mat image;   // the thermal image if the source had one (for overlays / dataset bags)
  std::vector<Eigen::Vector3f> points;  // P^h, LiDAR frame
  std::vector<std::int32_t> labels;     // kept for dataset bags and overlays
  int people = 0;                       // people count agreed by both modalities
  // Timing (issue 21). Point i was captured at cloud_stamp_s + point_time_s[i] (at cloud_stamp_s
  // when point_time_s is empty) and moves at point_velocity[i] relative to the LiDAR (empty: not
  // measured); the image was captured at stamp_s + delta. So at the image's instant the point
  // was at p + v (stamp_s + delta - cloud_stamp_s - point_time_s[i]) (person_timing.hpp).
  double cloud_stamp_s = 0.0;
  std::vector<float> point_time_s;
  std::vector<Eigen::Vector3f> point_velocity;
  // The vehicle's yaw rate about the LiDAR's z axis (PersonMotion::turn_rate_rps): the velocities
  // turn with it, so a point moves on p + v T + a T^2 / 2 with a = w (v_y, -v_x, 0).
  double turn_rate_rps = 0.0;
  std::vector<PersonMotion> motion;     // per person (label) of the pair: how it was measured
  // Issue 23. The rule that made the pair; the frame's place among the synchronized candidate
  // frames offered (skipped ones included: the skip rule for association pairs); and, for a
  // frame kept as a candidate for association, the mask's person regions (personRegions,
  // CV_16UC1) with `mask` left empty until an association makes it a pair.
  PairRule rule = PairRule::kCounts;
  std::uint64_t candidate_index = 0;
  cv::Mat regions;
  // Issue 24: a frame or pair the skip rule would not have made: a frame it passed over (held by
  // DatasetBuilder::keepSkippedFrames for the association's final round), or a pair that round
  // made within skip_frames of another. Its people stand a few centimetres from where the frame
  // beside it saw them: it adds ring heights, not an independent scene, so the bootstrap leaves
  // such pairs out.
  bool outside_skip_rule = false;
  // `mask`'s distance map, when a caller built it once for every evaluator of the pair
  // (sharedDistanceMap: the association's rounds, the quality, the truth's loss, the drift watch's
  // windows); empty: each LossEvaluator builds its own.
  // Whoever changes `mask` resets it.
  std::shared_ptr<const DistanceMap> distance_map;
};

}  // namespace thermal_lidar_calibration
