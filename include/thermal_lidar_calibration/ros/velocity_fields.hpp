#pragma once
// The people's measured motion kept with their clusters (issue 21): a kept pair's clusters in the
// dataset bag carry three float32 fields vx, vy, vz per point, its person's velocity relative to
// the LiDAR as the points are moved with it (deskewVelocity: vz is 0; m/s; 0 where not measured), so that a resumed node, or calibrate_bag on the dataset
// bag, can estimate the camera's time offset without the scans between kept frames, which the
// dataset bag does not hold. Two more, vx_se and vy_se, carry the standard errors of vx and vy
// (NaN where not measured): the timing's resolution discounts what the velocities' own errors
// would add (timing_resolution.hpp), so a dataset read back must have them to be judged as the
// session that kept it judged it. decodeClusters reads them back; motionFromFields makes the
// people's motion of them.

#include "thermal_lidar_calibration/core/person_motion.hpp"

#include <sensor_msgs/PointCloud2.h>

#include <string>
#include <vector>

namespace thermal_lidar_calibration {
namespace ros_io {

constexpr const char* kVelocityFields[3] = {"vx", "vy", "vz"};
constexpr const char* kVelocityErrorFields[2] = {"vx_se", "vy_se"};

// `clusters` with vx, vy, vz appended to every point from its label's motion (a label without a
// measured motion gets 0); existing velocity fields are replaced. Throws std::invalid_argument
// naming `topic` on a cloud whose layout is broken.
sensor_msgs::PointCloud2 withVelocityFields(const sensor_msgs::PointCloud2& clusters,
                                            const std::vector<PersonMotion>& motion, const std::string& topic);

// The measured people of a decoded cloud with those fields (`velocity`, `velocity_se` per point,
// as decodeClusters gives them): per label, its velocity and standard errors, scans 2 (the bag
// does not say how many; 2 is what makes the motion measured). Empty without the error fields
// (a dataset bag from before them: the velocities stay, without their errors).
std::vector<PersonMotion> motionFromFields(const std::vector<std::int32_t>& labels,
                                           const std::vector<Eigen::Vector3f>& velocity,
                                           const std::vector<Eigen::Vector2f>& velocity_se);

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
