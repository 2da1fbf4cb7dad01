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

// The velocity a person's points are moved with: the fitted one without its part along the
// LiDAR's z axis (its spin axis). The rings cut a person at fixed elevation angles, so each
// ring's points lie at a height set by the range alone (z = r tan(elevation)), and the cluster's
// centroid rises or sinks as the range changes and steps as rings come onto or off the body: its
// vertical rate measures the scan pattern, not the person. On the synthetic field drives it is
// 13-19 cm/s rms about a true 0 for the people in view (the horizontal rate: 4-5 cm/s), and
// moving points by it put each person a few millimetres up or down at a 60 ms offset, which the
// fit turned into centimetres of camera height. People walk on the ground and the vehicle drives
// on it, so what the camera sees change between the scan and the image is the horizontal part.
Eigen::Vector3d deskewVelocity(const PersonMotion& motion);
// Its standard error per axis (0 along z, which deskewVelocity does not use).
Eigen::Vector3d deskewVelocityStdError(const PersonMotion& motion);

// The pair carries one velocity per point (some may be zero: people not measured).
bool hasMeasuredMotion(const CalibrationPair& pair);

// Sets pair.motion, pair.point_velocity (deskewVelocity) from each point's label (people
// without a measurement, or labels not in `motion`, get zero velocity) and pair.turn_rate_rps
// (the measured people's, 0 without any).
void attachMotion(CalibrationPair& pair, std::vector<PersonMotion> motion);

// The seconds from point i's capture to the image's stamp: t - cloud_stamp - point_time[i].
double leadTimeS(const CalibrationPair& pair, std::size_t point);

// The bend of a point moving at `velocity` while the vehicle turns at `turn_rate_rps`: the
// acceleration w (v_y, -v_x, 0) (PersonMotion::turn_rate_rps).
Eigen::Vector3f turnAcceleration(const Eigen::Vector3f& velocity, double turn_rate_rps);

// The pair's points at the image's instant for `time_offset_s` (as captured without motion):
// p + v T + turnAcceleration(v) T^2 / 2, T = leadTimeS + time_offset_s.
std::vector<Eigen::Vector3f> pointsAtImageTime(const CalibrationPair& pair, double time_offset_s);

// Copies of the pairs with their points at the image's instant (masks and images shared): what
// a consumer that only reads positions (overlays, report, coverage) should draw.
std::vector<CalibrationPair> pairsAtImageTime(const std::vector<CalibrationPair>& pairs,
                                              double time_offset_s);

}  // namespace thermal_lidar_calibration
