#include "thermal_lidar_calibration/tools/synthetic_truth_file.hpp"

#include "thermal_lidar_calibration/app/files/result_file.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <stdexcept>

namespace thermal_lidar_calibration {
namespace ros_io {

namespace {

// The top-level extrinsic keys stay the one in force at the start (what existing readers use);
// this block says when it changed and to what.
void emitChange(YAML::Emitter& out, const synthetic::ExtrinsicChange& change) {
  if (!change.enabled) return;
  out << YAML::Key << "extrinsic_change" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "at_stamp" << YAML::Value << change.at_stamp_s;
  out << YAML::Key << "at_seconds_from_start" << YAML::Value << change.at_s;
  out << YAML::Key << "first_frame" << YAML::Value << change.first_frame;
  out << YAML::Key << "rotation_deg" << YAML::Value << change.rotation_deg;
  out << YAML::Key << "translation_cm" << YAML::Value << change.translation_cm;
  emitVector(out, "axis", change.axis.data(), 3);
  emitVector(out, "translation_direction", change.translation_direction.data(), 3);
  out << YAML::Key << "after" << YAML::Value << YAML::BeginMap;
  emitExtrinsic(out, change.after);
  out << YAML::EndMap;
  out << YAML::EndMap;
}

// Issue 21: what the sensors' clocks did. time_offset_s is the INTERFACE's delta when every LiDAR
// point is taken at its own capture time (stamp + per-point time); a fit that takes every point
// at its scan's stamp sees, for people near the image centre, time_offset_at_scan_stamp_s
// instead: the offset minus when the sweep passed the camera's axis.
void emitTiming(YAML::Emitter& out, const synthetic::SyntheticRig& rig) {
  const synthetic::SyntheticConfig& c = rig.config();
  const synthetic::SensorTimingConfig& timing = c.timing;
  out << YAML::Key << "time_offset_s" << YAML::Value << timing.camera_time_offset_s;
  out << YAML::Key << "lidar_stamp" << YAML::Value << synthetic::toString(timing.lidar_stamp);
  out << YAML::Key << "lidar_point_time" << YAML::Value << timing.lidar_point_time;
  // The camera's optical axis (+z of the camera) in the LiDAR frame, as an azimuth.
  const Eigen::Vector3d axis = c.rig.truth.rotationMatrix().transpose() * Eigen::Vector3d::UnitZ();
  const double axis_azimuth = std::atan2(axis.y(), axis.x());
  out << YAML::Key << "camera_axis_azimuth_deg" << YAML::Value << axis_azimuth * 180.0 / M_PI;
  double axis_time_s = 0.0;
  if (const synthetic::LidarSweep* sweep = rig.sweep()) {
    axis_time_s = sweep->timeFromStampAt(axis_azimuth);
    out << YAML::Key << "lidar_sweep_period_s" << YAML::Value << timing.lidar_period_s;
    out << YAML::Key << "lidar_sweep_direction" << YAML::Value << "clockwise";
    out << YAML::Key << "lidar_cut_azimuth_deg" << YAML::Value << timing.lidar_cut_azimuth_rad * 180.0 / M_PI;
    out << YAML::Key << "lidar_first_point_s" << YAML::Value << sweep->firstPointFromStamp();
    out << YAML::Key << "lidar_last_point_s" << YAML::Value << sweep->lastPointFromStamp();
  }
  out << YAML::Key << "camera_axis_scan_time_s" << YAML::Value << axis_time_s;
  out << YAML::Key << "time_offset_at_scan_stamp_s" << YAML::Value << timing.camera_time_offset_s - axis_time_s;
  out << YAML::Key << "speed_profile" << YAML::Value << synthetic::toString(c.scene.speed_profile);
  out << YAML::Key << "max_speed_mps" << YAML::Value << rig.scene().schedule().maxSpeed();
  out << YAML::Key << "walking_fraction" << YAML::Value << c.scene.walking_fraction;
}

}  // namespace

void writeSyntheticTruth(const MakeSyntheticBagOptions& o, const synthetic::SyntheticRig& rig) {
  const synthetic::SyntheticConfig& c = rig.config();
  YAML::Emitter out;
  out.SetDoublePrecision(15);
  out << YAML::Comment("Ground truth of a make_synthetic_bag run: p_C = R p_L + t (metres, radians)");
  out << YAML::BeginMap;
  out << YAML::Key << "lidar_frame" << YAML::Value << o.lidar_frame;
  out << YAML::Key << "camera_frame" << YAML::Value << o.camera_frame;
  emitExtrinsic(out, c.rig.truth);
  out << YAML::Key << "rig" << YAML::Value << c.rig.name;
  out << YAML::Key << "rig_description" << YAML::Value << c.rig.description;
  out << YAML::Key << "lidar_model" << YAML::Value << c.rig.lidar.name;
  out << YAML::Key << "lidar_height_m" << YAML::Value << c.rig.lidar_height_m;
  out << YAML::Key << "seed" << YAML::Value << c.seed;
  out << YAML::Key << "frames" << YAML::Value << c.frames;
  out << YAML::Key << "frame_rate_hz" << YAML::Value << c.frame_rate_hz;
  out << YAML::Key << "people" << YAML::Value << rig.scene().people().size();
  out << YAML::Key << "noise" << YAML::Value << o.noise;
  out << YAML::Key << "range_noise_m" << YAML::Value << c.noise.range_sigma_m;
  out << YAML::Key << "mask_edge_px" << YAML::Value << c.noise.mask_edge_px;
  out << YAML::Key << "mask_edge_sign" << YAML::Value << synthetic::toString(c.noise.mask_edge_sign);
  out << YAML::Key << "mask_erosion_part" << YAML::Value << synthetic::toString(c.noise.mask_erosion_part);
  out << YAML::Key << "miss_rate" << YAML::Value << c.noise.miss_rate;
  out << YAML::Key << "false_cluster_rate" << YAML::Value << c.noise.false_cluster_rate;
  out << YAML::Key << "false_mask_rate" << YAML::Value << c.noise.false_mask_rate;
  const auto& cam = c.rig.camera;
  out << YAML::Key << "image_width" << YAML::Value << cam.width;
  out << YAML::Key << "image_height" << YAML::Value << cam.height;
  const double camera_matrix[9] = {cam.fx, cam.skew, cam.cx, 0.0, cam.fy, cam.cy, 0.0, 0.0, 1.0};
  emitVector(out, "camera_matrix", camera_matrix, 9);
  out << YAML::Key << "distortion_model" << YAML::Value << "plumb_bob";
  emitVector(out, "distortion_coefficients", cam.distortion.data(), 5);
  out << YAML::Key << "bag" << YAML::Value << o.output;
  emitTiming(out, rig);
  emitChange(out, rig.extrinsicChange());
  const synthetic::ColumnRange empty = rig.emptyColumns();
  if (empty.end > empty.begin) {
    out << YAML::Key << "empty_image_region" << YAML::Value << synthetic::toString(c.empty_image_region);
    // First and last column of the region, inclusive.
    out << YAML::Key << "empty_image_columns" << YAML::Value << YAML::Flow << YAML::BeginSeq << empty.begin
        << empty.end - 1 << YAML::EndSeq;
  }
  out << YAML::EndMap;
  std::ofstream file(o.truth);
  if (!file) throw std::runtime_error("cannot write truth file '" + o.truth + "'");
  file << out.c_str() << "\n";
  if (!file) throw std::runtime_error("failed writing truth file '" + o.truth + "'");
}

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
