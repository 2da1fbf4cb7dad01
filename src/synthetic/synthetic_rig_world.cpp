// SyntheticRig: the world each sensor sees in a frame, at its own instants (issue 21): the
// camera at the stamp plus its offset, the LiDAR at the stamp or, swept, sector by sector; and
// the people's motion relative to the LiDAR.

#include "thermal_lidar_calibration/synthetic/synthetic_rig.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace thermal_lidar_calibration {
namespace synthetic {
namespace {

constexpr double kWorldCullM = 100.0;  // objects farther than this from the vehicle are dropped

}  // namespace

Eigen::Isometry3d SyntheticRig::lidarFromWorld(double t_s) const {
  const VehiclePose vehicle = scene_->vehicleAt(t_s);
  Eigen::Isometry3d T_world_lidar = Eigen::Isometry3d::Identity();
  T_world_lidar.translate(Eigen::Vector3d(vehicle.xy.x(), vehicle.xy.y(), config_.rig.lidar_height_m));
  T_world_lidar.rotate(Eigen::AngleAxisd(vehicle.yaw_rad, Eigen::Vector3d::UnitZ()));
  return T_world_lidar.inverse();
}

std::vector<SyntheticRig::ObjectRef> SyntheticRig::objectsNear(double t_s) const {
  const Eigen::Vector2d vehicle = scene_->vehicleAt(t_s).xy;
  std::vector<ObjectRef> refs;
  const auto& people = scene_->people();
  for (std::size_t i = 0; i < people.size(); ++i) {
    if ((people[i].poseAt(t_s).ground_xy - vehicle).norm() > kWorldCullM) continue;
    refs.push_back({ObjectRef::Kind::kPerson, i});
  }
  const auto& clutter = scene_->clutter();
  for (std::size_t i = 0; i < clutter.size(); ++i) {
    if ((clutter[i].solid.boundingCentre().head<2>() - vehicle).norm() > kWorldCullM) continue;
    refs.push_back({ObjectRef::Kind::kClutter, i});
  }
  for (std::size_t i = 0; i < confounders_.size(); ++i) {
    if ((confounders_[i].solid.boundingCentre().head<2>() - vehicle).norm() > kWorldCullM) continue;
    refs.push_back({ObjectRef::Kind::kConfounder, i});
  }
  return refs;
}

WorldObject SyntheticRig::place(const ObjectRef& ref, const Eigen::Isometry3d& T_lidar_world, double t_s) const {
  WorldObject obj;
  switch (ref.kind) {
    case ObjectRef::Kind::kPerson: {
      const PersonTrack& person = scene_->people()[ref.index];
      obj.solid = makePersonBody(person.poseAt(t_s)).transformed(T_lidar_world);
      obj.person_id = person.id;
      obj.grey_level = person_grey_[ref.index];
      break;
    }
    case ObjectRef::Kind::kClutter: {
      const ClutterItem& item = scene_->clutter()[ref.index];
      obj.solid = item.solid.transformed(T_lidar_world);
      obj.clutter_id = item.id;
      obj.grey_level = 72.0 + 7.0 * (item.id % 5);
      // Raw data: every fourth post or bush is sun-heated into the body band (~300 K), a warm
      // confounder only its shape tells from a person.
      if (config_.raw && item.id % 4 == 0) obj.grey_level = 180.0 + 3.0 * (item.id % 5);
      break;
    }
    case ObjectRef::Kind::kConfounder: {
      const Confounder& c = confounders_[ref.index];
      obj.solid = c.solid.transformed(T_lidar_world);
      obj.clutter_id = c.id;
      obj.grey_level = c.grey_level;
      break;
    }
  }
  return obj;
}

std::vector<WorldObject> SyntheticRig::worldAt(double stamp_s) const {
  const double t = stamp_s - config_.start_stamp_s;
  const Eigen::Isometry3d T_lidar_world = lidarFromWorld(t);
  std::vector<WorldObject> objects;
  for (const ObjectRef& ref : objectsNear(t)) objects.push_back(place(ref, T_lidar_world, t));
  return objects;
}

SyntheticRig::FrameWorld SyntheticRig::frameWorld(int index) const {
  FrameWorld world;
  world.scan_time_s = index / config_.frame_rate_hz;
  const double t_camera = world.scan_time_s + config_.timing.camera_time_offset_s;
  const std::vector<ObjectRef> lidar_refs = objectsNear(world.scan_time_s);
  const Eigen::Isometry3d T_scan = lidarFromWorld(world.scan_time_s);
  for (const ObjectRef& ref : lidar_refs) world.lidar.push_back(place(ref, T_scan, world.scan_time_s));
  if (t_camera == world.scan_time_s) {
    world.objects = world.lidar;
    for (std::size_t k = 0; k < world.lidar.size(); ++k) world.lidar_object.push_back(static_cast<int>(k));
  } else {
    const std::vector<ObjectRef> camera_refs = objectsNear(t_camera);
    const Eigen::Isometry3d T_camera = lidarFromWorld(t_camera);
    for (const ObjectRef& ref : camera_refs) world.objects.push_back(place(ref, T_camera, t_camera));
    for (std::size_t k = 0; k < lidar_refs.size(); ++k) {
      const auto seen = std::find(camera_refs.begin(), camera_refs.end(), lidar_refs[k]);
      if (seen != camera_refs.end()) {
        world.lidar_object.push_back(static_cast<int>(seen - camera_refs.begin()));
      } else {  // out of the camera's world at its instant: the LiDAR's alone
        world.lidar_object.push_back(static_cast<int>(world.objects.size()));
        world.objects.push_back(world.lidar[k]);
      }
    }
    world.camera_count = camera_refs.size();
  }
  if (t_camera == world.scan_time_s) world.camera_count = world.objects.size();
  if (sweep_) world.lidar_refs = lidar_refs;
  removePeopleSeenInEmptyRegion(world, index);
  return world;
}

std::vector<WorldObject> SyntheticRig::snapshot(int index) const { return frameWorld(index).lidar; }

// Each sector's azimuths see the objects where they were at the sector's middle instant (see
// LidarSweep for why that is close enough). An object is placed only for the sectors its
// bounding sphere can reach while the head sweeps: its azimuth window at the stamp, widened by
// how far it can move relative to the LiDAR within one rotation.
std::vector<LidarReturn> SyntheticRig::castSweptScan(const FrameWorld& world) const {
  const LidarModel& lidar = config_.rig.lidar;
  const LidarSweep& sweep = *sweep_;
  const double period = config_.timing.lidar_period_s;
  const double max_speed = scene_->schedule().maxSpeed();
  const SceneConfig& sc = config_.scene;
  // Relative displacement within a rotation (vehicle plus walker) and the turn of the frame.
  const double slack_m = (max_speed + sc.max_walk_speed_mps) * period + 0.2;
  const double max_curvature = 1.0 / sc.turn_radius_m + 0.05;  // turns plus the field's meander
  const double slack_rad = max_speed * max_curvature * period + 0.02;
  const double az_step = 2.0 * M_PI / lidar.azimuth_count;

  std::vector<std::vector<std::size_t>> in_sector(LidarSweep::kSectors);
  for (std::size_t k = 0; k < world.lidar.size(); ++k) {
    const Solid& solid = world.lidar[k].solid;
    const Eigen::Vector3d& c = solid.boundingCentre();
    const double reach = solid.boundingRadius() + slack_m;
    const double horiz = c.head<2>().norm();
    std::vector<char> touched(LidarSweep::kSectors, 0);
    if (horiz <= reach) {
      std::fill(touched.begin(), touched.end(), 1);
    } else {
      const double az_c = std::atan2(c.y(), c.x());
      const double half = std::asin(reach / horiz) + slack_rad;
      const int a_begin = static_cast<int>(std::floor((az_c - half) / az_step));
      const int a_end = static_cast<int>(std::ceil((az_c + half) / az_step));
      for (int ai = a_begin; ai <= a_end; ++ai) {
        const int a = ((ai % lidar.azimuth_count) + lidar.azimuth_count) % lidar.azimuth_count;
        touched[static_cast<std::size_t>(sweep.sectorOf(a))] = 1;
      }
    }
    for (int s = 0; s < LidarSweep::kSectors; ++s) {
      if (touched[static_cast<std::size_t>(s)]) in_sector[static_cast<std::size_t>(s)].push_back(k);
    }
  }

  ScanGrid grid(lidar, groundZ());
  for (int s = 0; s < LidarSweep::kSectors; ++s) {
    if (in_sector[static_cast<std::size_t>(s)].empty()) continue;
    const double t = world.scan_time_s + sweep.sectorTimeFromStamp(s);
    const Eigen::Isometry3d T_lidar_world = lidarFromWorld(t);
    for (const std::size_t k : in_sector[static_cast<std::size_t>(s)]) {
      const WorldObject obj = place(world.lidar_refs[k], T_lidar_world, t);
      grid.cast(obj.solid, world.lidar_object[k], &sweep.sectorOfAzimuth(), s);
    }
  }
  return grid.returns();
}

void SyntheticRig::removePeopleSeenInEmptyRegion(FrameWorld& world, int index) const {
  if (config_.empty_image_region == ImageRegion::kNone) return;
  // A margin keeps range noise and mask edge noise from carrying a person across the border.
  constexpr int kMarginPx = 2;
  const ColumnRange columns = emptyColumns();
  const ColumnRange wide{columns.begin - kMarginPx, columns.end + kMarginPx};
  // Removing a person can uncover one behind them: repeat until nobody shows there. A person
  // leaves both sensors' worlds.
  for (;;) {
    const Observation seen = observe(world, index);
    std::vector<char> remove(world.objects.size(), 0);
    for (int v = 0; v < seen.owners.rows; ++v) {
      const int* own = seen.owners.ptr<int>(v);
      for (int u = std::max(0, wide.begin); u < std::min(seen.owners.cols, wide.end); ++u) {
        if (own[u] >= 0 && world.objects[static_cast<std::size_t>(own[u])].isPerson()) remove[own[u]] = 1;
      }
    }
    for (const auto& r : seen.returns) {
      if (r.object < 0 || remove[r.object] || !world.objects[static_cast<std::size_t>(r.object)].isPerson()) continue;
      if (projectsIntoEmptyRegion(r.point, index, kMarginPx)) remove[r.object] = 1;
    }
    if (std::find(remove.begin(), remove.end(), 1) == remove.end()) return;
    FrameWorld kept;
    kept.scan_time_s = world.scan_time_s;
    std::vector<int> new_index(world.objects.size(), -1);
    for (std::size_t j = 0; j < world.objects.size(); ++j) {
      if (remove[j]) continue;
      if (j < world.camera_count) ++kept.camera_count;
      new_index[j] = static_cast<int>(kept.objects.size());
      kept.objects.push_back(std::move(world.objects[j]));
    }
    for (std::size_t k = 0; k < world.lidar.size(); ++k) {
      const int j = new_index[static_cast<std::size_t>(world.lidar_object[k])];
      if (j < 0) continue;
      kept.lidar.push_back(std::move(world.lidar[k]));
      kept.lidar_object.push_back(j);
      if (!world.lidar_refs.empty()) kept.lidar_refs.push_back(world.lidar_refs[k]);
    }
    world = std::move(kept);
  }
}

PersonMotion SyntheticRig::personMotion(int person_id, double stamp_s) const {
  const auto& people = scene_->people();
  const auto it = std::find_if(people.begin(), people.end(), [&](const PersonTrack& p) { return p.id == person_id; });
  if (it == people.end()) {
    throw std::invalid_argument("no person " + std::to_string(person_id) + " in this drive (ids 1.." +
                                std::to_string(people.size()) + ")");
  }
  const double t = stamp_s - config_.start_stamp_s;
  const VehicleMotion vehicle = scene_->vehicleMotionAt(t);
  const Eigen::Matrix2d R = Eigen::Rotation2Dd(vehicle.pose.yaw_rad).toRotationMatrix();
  const Eigen::Vector2d p = R.transpose() * (it->poseAt(t).ground_xy - vehicle.pose.xy);
  // d/dt R^T (x_person - x_vehicle) = R^T (v_person - v_vehicle) - w J p, J = rotation by +90 deg.
  const Eigen::Vector2d v = R.transpose() * (it->velocityAt(t) - vehicle.velocity_mps) -
                            vehicle.yaw_rate_radps * Eigen::Vector2d(-p.y(), p.x());
  PersonMotion m;
  m.person_id = person_id;
  m.position_m = Eigen::Vector3d(p.x(), p.y(), groundZ() + 0.5 * it->height_m);
  m.velocity_mps = Eigen::Vector3d(v.x(), v.y(), 0.0);
  return m;
}

}  // namespace synthetic
}  // namespace thermal_lidar_calibration
