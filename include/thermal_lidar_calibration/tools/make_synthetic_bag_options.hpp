#pragma once
// Command line of make_synthetic_bag, and the rig configuration it asks for.

#include "thermal_lidar_calibration/synthetic/synthetic_rig.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace thermal_lidar_calibration {
namespace ros_io {

struct MakeSyntheticBagOptions {
  std::string output;              // bag to write
  std::string truth;               // truth YAML (default <output>.truth.yaml)
  std::string rig = "fieldsafe";   // fieldsafe | ms2
  std::uint64_t seed = 1;
  int frames = synthetic::SyntheticConfig{}.frames;
  int people = 0;                  // 0 = automatic (about 1.8 per group)
  std::string noise = "clean";     // clean | realistic
  // Overrides of the noise preset; negative = keep the preset's value.
  double range_noise_m = -1, miss_rate = -1, false_cluster_rate = -1, false_mask_rate = -1;
  int mask_edge_px = -1;
  std::string mask_edge_sign = "both";  // both | grow | shrink
  std::string mask_erosion_part = "all";  // all | thin | outline
  std::string mask_style = "ids";        // ids | binary
  std::string image_encoding = "mono8";  // mono8 | mono16
  bool full_cloud = false;
  bool raw = false;  // --raw: full-density /lidar/points and a radiometric mono16 image
  bool camera_info = true;
  std::string camera_parent;       // non-empty: write /tf_static camera_parent -> camera frame
  double time_jitter_s = 0.0;
  std::string lidar_frame = "velodyne";
  std::string camera_frame = "thermal_optical";
  double extrinsic_change_at_s = -1.0;  // < 0: no change
  double extrinsic_change_rotation_deg = 0.0;
  double extrinsic_change_translation_cm = 0.0;
  std::string empty_image_region = "none";  // none | left | centre | right
  // Issue 21: sensor timing and how the vehicle drives.
  double camera_time_offset_s = 0.0;    // the image stamped t shows the world at t + this
  bool lidar_point_time = false;        // a float32 `time` per point (the scan sweeps)
  std::string lidar_stamp = "instant";  // instant | start | end (--lidar-point-time alone: end)
  double lidar_cut_azimuth_deg = 180.0; // where a sweep starts, counter-clockwise from forward
  std::string speed_profile = "steady"; // steady | field
  double walking_fraction = -1.0;       // share of people walking; < 0: the scene's default
  bool help = false;
};

// Throws UsageError (calibrate_bag_options.hpp) with a one-line reason. With --help, returns
// options with help = true and nothing else checked.
MakeSyntheticBagOptions parseMakeSyntheticBagOptions(const std::vector<std::string>& args);
std::string makeSyntheticBagUsage();

// The rig configuration the options ask for (the rig validates it when constructed).
synthetic::SyntheticConfig syntheticConfigFrom(const MakeSyntheticBagOptions& options);

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
