#pragma once
// Writes the frames of a synthetic drive into a ROS 1 bag (LZ4) under the INTERFACE topics:
// /thermal/image_raw, /thermal/camera_info, /thermal/human_mask, /lidar/human_clusters, and
// optionally /lidar/points and a latched /tf_static.

#include "thermal_lidar_calibration/synthetic/synthetic_rig.hpp"

#include <rosbag/bag.h>
#include <sensor_msgs/CameraInfo.h>

#include <string>

namespace thermal_lidar_calibration {
namespace ros_io {

struct SyntheticBagSettings {
  std::string lidar_frame = "velodyne";
  std::string camera_frame = "thermal_optical";
  std::string camera_parent;  // non-empty: one latched /tf_static camera_parent -> camera frame
  bool camera_info = true;    // write /thermal/camera_info beside every image
  double time_jitter_s = 0.0; // each topic's stamp moves by a random +-this per frame
};

class SyntheticBagWriter {
 public:
  // Opens (truncates) the bag and writes the /tf_static message if asked for. Throws
  // rosbag::BagException when the file cannot be written.
  SyntheticBagWriter(const std::string& path, SyntheticBagSettings settings,
                     const synthetic::SyntheticConfig& config);
  // Frames must come in index order (the bag is written in time order).
  void write(const synthetic::SyntheticFrame& frame);
  void close();

 private:
  SyntheticBagSettings settings_;
  synthetic::SyntheticConfig config_;
  sensor_msgs::CameraInfo info_template_;
  rosbag::Bag bag_;
};

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
