#pragma once
// The people's measured motion kept with their clusters (issue 21): a kept pair's clusters in the
// dataset bag carry three float32 fields vx, vy, vz per point, its person's velocity relative to
// the LiDAR as the points are moved with it (deskewVelocity: vz is 0; m/s; 0 where not measured), so that a resumed node, or calibrate_bag on the dataset
// bag, can estimate the camera's time offset without the scans between kept frames, which the
// dataset bag does not hold. decodeClusters reads them back.

#include "thermal_lidar_calibration/core/person_motion.hpp"

#include <sensor_msgs/PointCloud2.h>

#include <string>
#include <vector>

namespace thermal_lidar_calibration {
namespace ros_io {

constexpr const char* kVelocityFields[3] = {"vx", "vy", "vz"};

// `clusters` with vx, vy, vz appended to every point from its label's motion (a label without a
// measured motion gets 0); existing velocity fields are replaced. Throws std::invalid_argument
// naming `topic` on a cloud whose layout is broken.
sensor_msgs::PointCloud2 withVelocityFields(const sensor_msgs::PointCloud2& clusters,
                                            const std::vector<PersonMotion>& motion, const std::string& topic);

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
