#pragma once
// Where a pair's LiDAR points were at the instant its image was captured (issue 21). The image
// stamped t was captured at t + delta on the LiDAR's clock (delta = time_offset_s, INTERFACE.md);
// point i was captured at cloud_stamp + point_time[i] and moves with its person at v_i relative
// to the LiDAR, so at the image's instant it was at
//     p_i + v_i (t + delta - cloud_stamp - point_time[i]).
// Without measured motion a pair's points stay where they were captured. ROS-free.

#include "thermal_lidar_calibration/core/calibration_pair.hpp"
#include "thermal_lidar_calibration/core/person_motion.hpp"

#include <vector>

namespace thermal_lidar_calibration {

// The pair carries one velocity per point (some may be zero: people not measured).
bool hasMeasuredMotion(const CalibrationPair& pair);

// Sets pair.motion and pair.point_velocity from each point's label (people without a
// measurement, or labels not in `motion`, get zero velocity).
void attachMotion(CalibrationPair& pair, std::vector<PersonMotion> motion);

// The seconds from point i's capture to the image's stamp: t - cloud_stamp - point_time[i].
double leadTimeS(const CalibrationPair& pair, std::size_t point);

// The pair's points at the image's instant for `time_offset_s` (as captured without motion).
std::vector<Eigen::Vector3f> pointsAtImageTime(const CalibrationPair& pair, double time_offset_s);

// Copies of the pairs with their points at the image's instant (masks and images shared): what
// a consumer that only reads positions (overlays, report, coverage) should draw.
std::vector<CalibrationPair> pairsAtImageTime(const std::vector<CalibrationPair>& pairs,
                                              double time_offset_s);

}  // namespace thermal_lidar_calibration
