#pragma once
// The world: a flat open field (ground plane z = 0), a vehicle driving at constant speed along
// straight legs joined by turns (random +-15..45 deg, alternating left/right), small groups of
// people standing or walking slowly beside each leg, and some cold clutter (posts, bushes).
// Groups are ~62 m apart along the path so that, while the vehicle approaches one group (in the
// camera's view), the previous one is usually behind it and out of detection range; the turn
// comes just after each group, so every approach is straight. With the field speed profile
// (issue 21) the vehicle also stops and changes speed (DriveSchedule), its path meanders gently
// on every leg and its turns ease in and out, so it turns while people are in view.

#include "thermal_lidar_calibration/synthetic/body_model.hpp"
#include "thermal_lidar_calibration/synthetic/drive_schedule.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstdint>
#include <random>
#include <vector>

namespace thermal_lidar_calibration {
namespace synthetic {

struct SceneConfig {
  double duration_s = 60.0;          // how long the vehicle drives (sizes the path)
  double speed_mps = 2.5;            // vehicle speed along the path (field profile: its cruise speed)
  int people = 0;                    // total people; 0 = about 1.8 per group (automatic)
  double group_spacing_m = 62.0;     // along the path between consecutive groups
  double first_group_m = 28.0;       // arc length of the first group ahead of the start
  double min_lateral_m = 1.5;        // closest a person stands to the path centre line (near people, seen at 4-10 m, constrain the translation)
  double max_lateral_m = 7.0;        // farthest (some are then outside the camera's view)
  double min_height_m = 1.55;
  double max_height_m = 1.95;
  double walking_fraction = 0.35;    // share of people walking slowly (back and forth)
  double max_walk_speed_mps = 0.8;
  double turn_radius_m = 15.0;       // of the turns between legs
  double min_turn_rad = 0.26;        // turn angle range (about 15..45 deg)
  double max_turn_rad = 0.79;
  double turn_after_group_m = 8.0;   // the turn starts this far past each group
  int clutter_per_group = 1;         // posts/bushes placed near each group
  int people_side = 0;               // +1: people only left of the path, -1: only right, 0: either
  SpeedProfile speed_profile = SpeedProfile::kSteady;  // kField: speed_mps is the cruise speed
  void validate() const;             // throws std::invalid_argument
};

struct VehiclePose {
  Eigen::Vector2d xy = Eigen::Vector2d::Zero();  // world, m
  double yaw_rad = 0.0;                          // heading, about +z
};

struct VehicleMotion {
  VehiclePose pose;
  Eigen::Vector2d velocity_mps = Eigen::Vector2d::Zero();  // world
  double speed_mps = 0.0;
  // The path's turning rate times the speed. The field drive turns exactly so; the steady drive
  // turns in steps (its heading is that of 0.1 m chords, kept for the unchanged default bag), so
  // its rendered heading is within half a chord's turn (at most 0.0033 rad) of this rate's.
  double yaw_rate_radps = 0.0;
};

struct PersonTrack {
  int id = 0;                      // persistent, 1-based; used as the cluster label
  double height_m = 1.75;
  Eigen::Vector2d anchor_xy = Eigen::Vector2d::Zero();  // centre of the walk
  double heading_rad = 0.0;        // facing (and walking) direction
  double walk_speed_mps = 0.0;     // 0 = standing
  double walk_half_length_m = 0.0; // walks back and forth +- this along its heading
  double phase_s = 0.0;            // time offset of the walk cycle
  BodyPose poseAt(double t_s) const;
  Eigen::Vector2d velocityAt(double t_s) const;  // of ground_xy, world, m/s
};

struct ClutterItem {
  int id = 0;     // 1-based
  Solid solid;    // world frame
};

class Scene {
 public:
  Scene(const SceneConfig& config, std::uint64_t seed);

  // t_s: seconds of drive (any real: before 0 s the vehicle was already driving straight on at
  // its first speed and heading, so the field drive's yaw rate steps at 0 s; past the path's end
  // it stands).
  VehiclePose vehicleAt(double t_s) const;
  VehicleMotion vehicleMotionAt(double t_s) const;
  const DriveSchedule& schedule() const { return schedule_; }
  const std::vector<PersonTrack>& people() const { return people_; }
  const std::vector<ClutterItem>& clutter() const { return clutter_; }
  const SceneConfig& config() const { return config_; }

 private:
  VehiclePose poseAtArcLength(double s) const;
  // The path's heading and its rate of change with arc length (rad/m) at s (field: interpolated
  // between chords; steady: the chord's heading and 0).
  void headingAt(double s, double* heading_rad, double* rate_rad_per_m) const;
  // Curvature (1/m) the field profile adds at arc length s: a gentle meander.
  double meanderCurvature(double s) const;
  // The constructor's steps, drawing from one stream in this order: the path (straight legs, a
  // turn just after each group at arc lengths group_s), then the groups' people and clutter.
  void buildPath(const std::vector<double>& group_s, bool field, std::mt19937_64& rng);
  void placeGroups(const std::vector<double>& group_s, std::mt19937_64& rng);
  SceneConfig config_;
  DriveSchedule schedule_;
  std::vector<double> path_s_;           // arc length samples
  std::vector<Eigen::Vector2d> path_xy_;
  std::vector<double> path_heading_;     // [i]: heading of the chord from sample i-1 to i ([0]: the start's)
  double meander_amplitude_ = 0.0, meander_wavelength_m_ = 1.0, meander_phase_ = 0.0;
  std::vector<PersonTrack> people_;
  std::vector<ClutterItem> clutter_;
};

}  // namespace synthetic
}  // namespace thermal_lidar_calibration
