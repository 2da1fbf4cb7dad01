#include "thermal_lidar_calibration/synthetic/scene.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

namespace thermal_lidar_calibration {
namespace synthetic {
namespace {

constexpr double kPathStepM = 0.1;
constexpr double kStrideM = 1.4;  // one full gait cycle
constexpr double kMinSeparationM = 0.9;
// The field profile's meander: curvature A sin(2 pi s / wavelength + phase), so the heading swings
// by +-A wavelength / (2 pi) (about 0.2 rad) and the yaw rate at 2 m/s reaches 0.06 rad/s, as a
// tractor following a field's rows or contours.
constexpr double kMeanderCurvature = 0.03;  // 1/m

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("scene config: " + what);
}

}  // namespace

void SceneConfig::validate() const {
  require(duration_s > 0.0, "duration_s must be > 0");
  require(speed_mps > 0.0 && speed_mps < 40.0, "speed_mps must be in (0, 40)");
  require(people >= 0 && people <= 250, "people must be in [0, 250]");
  require(group_spacing_m >= 5.0, "group_spacing_m must be >= 5");
  require(min_lateral_m >= 1.0 && max_lateral_m >= min_lateral_m, "need 1 <= min_lateral_m <= max_lateral_m");
  require(min_height_m > 0.5 && max_height_m >= min_height_m && max_height_m < 2.5,
          "need 0.5 < min_height_m <= max_height_m < 2.5");
  require(walking_fraction >= 0.0 && walking_fraction <= 1.0, "walking_fraction must be in [0, 1]");
  require(max_walk_speed_mps >= 0.0 && max_walk_speed_mps <= 3.0, "max_walk_speed_mps must be in [0, 3]");
  require(turn_radius_m >= 3.0, "turn_radius_m must be >= 3");
  require(min_turn_rad >= 0.0 && max_turn_rad >= min_turn_rad && max_turn_rad <= M_PI, "bad turn angles");
  require(turn_after_group_m >= 0.0, "turn_after_group_m must be >= 0");
  require(clutter_per_group >= 0, "clutter_per_group must be >= 0");
  require(people_side >= -1 && people_side <= 1, "people_side must be -1, 0 or 1");
}

BodyPose PersonTrack::poseAt(double t_s) const {
  BodyPose pose;
  pose.height_m = height_m;
  pose.heading_rad = heading_rad;
  pose.ground_xy = anchor_xy;
  if (walk_speed_mps <= 0.0 || walk_half_length_m <= 0.0) return pose;
  // Back and forth along the heading: x(t) = L sin(w t), peak speed v = L w.
  const double w = walk_speed_mps / walk_half_length_m;
  const double theta = w * (t_s + phase_s);
  const Eigen::Vector2d dir(std::cos(heading_rad), std::sin(heading_rad));
  pose.ground_xy = anchor_xy + dir * walk_half_length_m * std::sin(theta);
  if (std::cos(theta) < 0.0) pose.heading_rad = heading_rad + M_PI;  // walking the other way
  // Distance walked so far (|dx/dtheta| integrated) drives the gait.
  const double half_turns = std::floor(theta / M_PI);
  const double rem = theta - half_turns * M_PI;
  const double walked = walk_half_length_m * (2.0 * half_turns + (1.0 - std::cos(rem)));
  pose.gait_phase_rad = 2.0 * M_PI * walked / kStrideM;
  pose.swing_rad = 0.35 * std::min(1.0, std::abs(std::cos(theta)) * 3.0);
  return pose;
}

Eigen::Vector2d PersonTrack::velocityAt(double t_s) const {
  if (walk_speed_mps <= 0.0 || walk_half_length_m <= 0.0) return Eigen::Vector2d::Zero();
  // d/dt of anchor + dir L sin(w (t + phase)), w = v / L.
  const double w = walk_speed_mps / walk_half_length_m;
  const Eigen::Vector2d dir(std::cos(heading_rad), std::sin(heading_rad));
  return dir * walk_speed_mps * std::cos(w * (t_s + phase_s));
}

Scene::Scene(const SceneConfig& config, std::uint64_t seed)
    : config_(config), schedule_(DriveSchedule::steady(config.speed_mps)) {
  config_.validate();
  const bool field = config_.speed_profile == SpeedProfile::kField;
  if (field) {
    // Streams of their own: the steady drive's draws below are the same with either profile.
    schedule_ = DriveSchedule::field(config_.speed_mps, config_.duration_s, seed ^ 0xf1e1d5c4ed01eULL);
    std::mt19937_64 meander_rng(seed ^ 0x3ea2de7a11ULL);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    meander_amplitude_ = kMeanderCurvature;
    meander_wavelength_m_ = 35.0 + 20.0 * unit(meander_rng);
    meander_phase_ = 2.0 * M_PI * unit(meander_rng);
  }
  // One stream for the path and the people, drawn in this order.
  std::mt19937_64 rng(seed ^ 0x5ce9e5ce9eULL);

  // Groups along the path, then the path: straight legs, a turn just after each group.
  const double drive_m = schedule_.arcLengthAt(config_.duration_s);
  std::vector<double> group_s;
  for (double gs = config_.first_group_m; gs < drive_m + 35.0; gs += config_.group_spacing_m) {
    group_s.push_back(gs);
  }
  buildPath(group_s, field, rng);
  placeGroups(group_s, rng);
}

void Scene::buildPath(const std::vector<double>& group_s, bool field, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  auto uniform = [&](double a, double b) { return a + (b - a) * unit(rng); };
  const double drive_m = schedule_.arcLengthAt(config_.duration_s);
  std::vector<double> turn_start, turn_curvature, turn_length;
  double turn_sign = unit(rng) < 0.5 ? -1.0 : 1.0;
  for (const double gs : group_s) {
    const double angle = uniform(config_.min_turn_rad, config_.max_turn_rad);
    turn_start.push_back(gs + config_.turn_after_group_m);
    turn_curvature.push_back(turn_sign / config_.turn_radius_m);
    // Field: the curvature eases in and out (sin^2, peaking at 1 / turn_radius_m), so the yaw
    // rate has no step; the turn is twice as long for the same angle.
    turn_length.push_back((field ? 2.0 : 1.0) * angle * config_.turn_radius_m);
    if (unit(rng) < 0.8) turn_sign = -turn_sign;  // mostly alternate: the path meanders onwards
  }
  const double needed_m = drive_m + config_.group_spacing_m + 40.0;
  double heading = uniform(-M_PI, M_PI);
  Eigen::Vector2d xy = Eigen::Vector2d::Zero();
  path_s_.push_back(0.0);
  path_xy_.push_back(xy);
  path_heading_.push_back(heading);
  std::size_t turn = 0;
  for (double s = kPathStepM; s <= needed_m; s += kPathStepM) {
    while (turn < turn_start.size() && s > turn_start[turn] + turn_length[turn]) ++turn;
    const double mid = s - 0.5 * kPathStepM;
    if (turn < turn_start.size() && mid >= turn_start[turn]) {
      double ease = 1.0;
      if (field) {
        const double x = std::sin(M_PI * (mid - turn_start[turn]) / turn_length[turn]);
        ease = x * x;
      }
      heading += ease * turn_curvature[turn] * kPathStepM;
    }
    if (field) heading += meanderCurvature(mid) * kPathStepM;
    xy += kPathStepM * Eigen::Vector2d(std::cos(heading), std::sin(heading));
    path_s_.push_back(s);
    path_xy_.push_back(xy);
    path_heading_.push_back(heading);
  }
}

void Scene::placeGroups(const std::vector<double>& group_s, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  auto uniform = [&](double a, double b) { return a + (b - a) * unit(rng); };
  const int groups = static_cast<int>(group_s.size());
  std::vector<int> group_size(groups, 0);
  if (config_.people > 0) {
    for (int i = 0; i < config_.people; ++i) ++group_size[i % groups];
  } else {
    for (int g = 0; g < groups; ++g) {
      const double u = unit(rng);
      group_size[g] = u < 0.42 ? 1 : (u < 0.78 ? 2 : 3);
    }
  }

  int next_id = 1;
  for (int g = 0; g < groups; ++g) {
    std::vector<Eigen::Vector2d> placed;
    for (int i = 0; i < group_size[g]; ++i) {
      PersonTrack person;
      person.id = next_id++;
      person.height_m = uniform(config_.min_height_m, config_.max_height_m);
      const bool walking = unit(rng) < config_.walking_fraction;
      for (int attempt = 0; attempt < 50; ++attempt) {
        const double along = group_s[g] + uniform(-4.0, 4.0);
        const VehiclePose at = poseAtArcLength(along);
        const Eigen::Vector2d tangent(std::cos(at.yaw_rad), std::sin(at.yaw_rad));
        const Eigen::Vector2d normal(-tangent.y(), tangent.x());
        double side = unit(rng) < 0.5 ? -1.0 : 1.0;  // drawn always: the other draws stay the same
        if (config_.people_side != 0) side = config_.people_side;
        double lateral = uniform(config_.min_lateral_m, config_.max_lateral_m);
        if (walking) {
          person.walk_speed_mps = uniform(0.3, std::max(0.3, config_.max_walk_speed_mps));
          person.walk_half_length_m = uniform(1.0, 3.0);
          const double deviation = uniform(-0.4, 0.4);  // walk roughly parallel to the path
          person.heading_rad = at.yaw_rad + deviation + (unit(rng) < 0.5 ? M_PI : 0.0);
          lateral += person.walk_half_length_m * std::abs(std::sin(deviation));
          person.phase_s = uniform(0.0, 100.0);
        } else {
          person.heading_rad = uniform(-M_PI, M_PI);
        }
        person.anchor_xy = at.xy + side * lateral * normal;
        bool clear = true;
        for (const auto& q : placed) {
          const double need = kMinSeparationM + (walking ? 2.0 * person.walk_half_length_m : 0.0);
          if ((q - person.anchor_xy).norm() < need) clear = false;
        }
        if (clear) break;
      }
      placed.push_back(person.anchor_xy);
      people_.push_back(person);
    }
    for (int c = 0; c < config_.clutter_per_group; ++c) {
      const double along = group_s[g] + (unit(rng) < 0.5 ? -1.0 : 1.0) * uniform(14.0, 24.0);
      const VehiclePose at = poseAtArcLength(along);
      const Eigen::Vector2d normal(-std::sin(at.yaw_rad), std::cos(at.yaw_rad));
      const Eigen::Vector2d xy = at.xy + (unit(rng) < 0.5 ? -1.0 : 1.0) * uniform(5.0, 12.0) * normal;
      ClutterItem item;
      item.id = static_cast<int>(clutter_.size()) + 1;
      if (unit(rng) < 0.5) {
        item.solid = makePost(xy, uniform(1.1, 1.8), uniform(0.07, 0.15));
      } else {
        item.solid = makeBush(xy, Eigen::Vector3d(uniform(0.35, 0.7), uniform(0.35, 0.7), uniform(0.45, 0.8)));
      }
      clutter_.push_back(item);
    }
  }
}

double Scene::meanderCurvature(double s) const {
  return meander_amplitude_ * std::sin(2.0 * M_PI * s / meander_wavelength_m_ + meander_phase_);
}

void Scene::headingAt(double s, double* heading_rad, double* rate_rad_per_m) const {
  *rate_rad_per_m = 0.0;
  if (config_.speed_profile != SpeedProfile::kField) {
    *heading_rad = poseAtArcLength(s).yaw_rad;
    return;
  }
  // Knots: the start's heading at x = 0, chord i's heading at its middle x = i - 0.5 (x in steps).
  const double x = std::max(0.0, s / kPathStepM);
  const std::size_t last = path_heading_.size() - 1;
  const std::size_t i = std::min<std::size_t>(static_cast<std::size_t>(std::floor(x + 0.5)), last);
  if (i == last) {
    *heading_rad = path_heading_[last];
    return;
  }
  const double x0 = i == 0 ? 0.0 : i - 0.5;
  const double x1 = i + 0.5;
  const double rate = (path_heading_[i + 1] - path_heading_[i]) / (x1 - x0);
  *heading_rad = path_heading_[i] + (x - x0) * rate;
  if (s >= 0.0) *rate_rad_per_m = rate / kPathStepM;
}

VehiclePose Scene::poseAtArcLength(double s) const {
  if (s < 0.0) {
    // Before the start the vehicle came straight along its heading at the start (the steady
    // drive's is its first chord's).
    VehiclePose pose;
    if (config_.speed_profile == SpeedProfile::kField) {
      pose.yaw_rad = path_heading_[0];
    } else {
      const Eigen::Vector2d d = path_xy_[1] - path_xy_[0];
      pose.yaw_rad = std::atan2(d.y(), d.x());
    }
    pose.xy = path_xy_[0] + s * Eigen::Vector2d(std::cos(pose.yaw_rad), std::sin(pose.yaw_rad));
    return pose;
  }
  s = std::min(s, path_s_.back());
  const auto it = std::upper_bound(path_s_.begin(), path_s_.end(), s);
  const std::size_t hi = std::min<std::size_t>(std::max<std::ptrdiff_t>(it - path_s_.begin(), 1), path_s_.size() - 1);
  const std::size_t lo = hi - 1;
  const double span = path_s_[hi] - path_s_[lo];
  const double f = span > 0.0 ? (s - path_s_[lo]) / span : 0.0;
  VehiclePose pose;
  pose.xy = path_xy_[lo] + f * (path_xy_[hi] - path_xy_[lo]);
  const Eigen::Vector2d d = path_xy_[hi] - path_xy_[lo];
  pose.yaw_rad = std::atan2(d.y(), d.x());
  if (config_.speed_profile == SpeedProfile::kField) {
    // The heading turns smoothly (not chord by chord), so the yaw rate is what vehicleMotionAt says.
    double rate = 0.0;
    headingAt(s, &pose.yaw_rad, &rate);
  }
  return pose;
}

VehiclePose Scene::vehicleAt(double t_s) const { return poseAtArcLength(schedule_.arcLengthAt(t_s)); }

VehicleMotion Scene::vehicleMotionAt(double t_s) const {
  const double s = schedule_.arcLengthAt(t_s);
  VehicleMotion m;
  m.pose = poseAtArcLength(s);
  if (s >= path_s_.back()) return m;  // the path ends: the vehicle stands
  m.speed_mps = schedule_.speedAt(t_s);
  m.velocity_mps = m.speed_mps * Eigen::Vector2d(std::cos(m.pose.yaw_rad), std::sin(m.pose.yaw_rad));
  double heading = 0.0, rate = 0.0;
  if (config_.speed_profile == SpeedProfile::kField) {
    headingAt(s, &heading, &rate);
  } else if (s >= 0.0) {
    // The steady path's own turning rate: the chord headings' change over the chords around s.
    const std::size_t i = std::min<std::size_t>(static_cast<std::size_t>(s / kPathStepM) + 1, path_heading_.size() - 2);
    rate = (path_heading_[i + 1] - path_heading_[i - 1]) / (2.0 * kPathStepM);
  }
  m.yaw_rate_radps = rate * m.speed_mps;
  return m;
}

}  // namespace synthetic
}  // namespace thermal_lidar_calibration
