#include "thermal_lidar_calibration/synthetic/synthetic_rig.hpp"

#include "thermal_lidar_calibration/core/frame_gate.hpp"
#include "thermal_lidar_calibration/core/person_counter.hpp"
#include "thermal_lidar_calibration/synthetic/lidar_scanner.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <stdexcept>
#include <string>

namespace thermal_lidar_calibration {
namespace synthetic {
namespace {

constexpr std::int32_t kFalseClusterLabelBase = 1000;

// Range noise along each ray (none when sigma is 0: no draw either).
void addRangeNoise(double sigma_m, std::mt19937_64& rng, std::vector<LidarReturn>* returns) {
  if (sigma_m <= 0.0) return;
  std::normal_distribution<double> gauss(0.0, sigma_m);
  for (auto& r : *returns) {
    const double noisy = std::max(0.05, r.range_m + gauss(rng));
    r.point *= static_cast<float>(noisy / r.range_m);
    r.range_m = static_cast<float>(noisy);
  }
}

}  // namespace

std::uint64_t mixSeed(std::uint64_t seed, std::uint64_t stream, std::uint64_t index) {
  std::uint64_t z = seed + 0x9E3779B97F4A7C15ULL * (stream + 1) + 0xBF58476D1CE4E5B9ULL * (index + 1);
  for (int i = 0; i < 2; ++i) {
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    z ^= z >> 31;
  }
  return z;
}

Extrinsic bumpedExtrinsic(const Extrinsic& e, const Eigen::Vector3d& axis, double degrees,
                          const Eigen::Vector3d& shift_m) {
  const Eigen::Matrix3d turn =
      Eigen::AngleAxisd(degrees * M_PI / 180.0, axis.normalized()).toRotationMatrix();
  return Extrinsic::fromRotationMatrix(turn * e.rotationMatrix(), e.translation + shift_m);
}

void SyntheticConfig::validate() const {
  if (frames < 1 || frames > 100000) throw std::invalid_argument("frames must be in [1, 100000]");
  if (!(frame_rate_hz > 0.0 && frame_rate_hz <= 100.0)) {
    throw std::invalid_argument("frame_rate_hz must be in (0, 100]");
  }
  if (full_cloud_azimuth_step < 1) throw std::invalid_argument("full_cloud_azimuth_step must be >= 1");
  if (detector.min_cluster_points < 1 || detector.min_mask_pixels < 1 || detector.detection_range_m <= 0.0) {
    throw std::invalid_argument("detector: need min_cluster_points >= 1, min_mask_pixels >= 1, range > 0");
  }
  if (extrinsic_change.enabled()) {
    const double duration_s = frames / frame_rate_hz;
    if (!(extrinsic_change.at_s > 0.0 && extrinsic_change.at_s < duration_s)) {
      throw std::invalid_argument("extrinsic change at " + std::to_string(extrinsic_change.at_s) +
                                  " s: must be inside the drive, (0, " + std::to_string(duration_s) + ") s");
    }
    if (!(extrinsic_change.rotation_deg >= 0.0 && extrinsic_change.rotation_deg <= 45.0 &&
          extrinsic_change.translation_cm >= 0.0 && extrinsic_change.translation_cm <= 100.0)) {
      throw std::invalid_argument("extrinsic change: rotation must be in [0, 45] deg, translation in [0, 100] cm");
    }
    if (extrinsic_change.rotation_deg == 0.0 && extrinsic_change.translation_cm == 0.0) {
      throw std::invalid_argument("extrinsic change of 0 deg and 0 cm changes nothing");
    }
  }
  rig.camera.validate();
  rig.lidar.validate();
  noise.validate();
  scene.validate();
  timing.validate();
}

SyntheticRig::SyntheticRig(const SyntheticConfig& config) : config_(config) {
  config_.scene.speed_mps = config_.rig.vehicle_speed_mps;
  config_.scene.duration_s = config_.frames / config_.frame_rate_hz;
  // The camera's left is the vehicle's left: people for an empty left third stand on the right.
  if (config_.empty_image_region == ImageRegion::kLeft) config_.scene.people_side = -1;
  if (config_.empty_image_region == ImageRegion::kRight) config_.scene.people_side = 1;
  config_.validate();
  scene_ = std::make_unique<Scene>(config_.scene, config_.seed);
  renderer_ = std::make_unique<ThermalRenderer>(config_.rig.camera, config_.rig.truth, groundZ());
  std::mt19937_64 rng(mixSeed(config_.seed, 7, 0));
  std::uniform_real_distribution<double> grey(185.0, 215.0);
  for (std::size_t i = 0; i < scene_->people().size(); ++i) person_grey_.push_back(grey(rng));
  drawChange();
  if (config_.raw) placeConfounders();
  if (config_.timing.swept()) sweep_ = std::make_unique<LidarSweep>(config_.timing, config_.rig.lidar.azimuth_count);
}

// What fools a thermal person detector besides sun-heated posts (issue 7): every 25 s of drive a
// parked vehicle (cool body, engine hotter than a person) or an animal (body temperature, four
// legs), 4-6 s ahead of the vehicle and 5-11 m to its side. Its own random stream: the people
// and the rest of the drive are the same as without them.
void SyntheticRig::placeConfounders() {
  constexpr int kConfounderIdBase = 500;
  std::mt19937_64 rng(mixSeed(config_.seed, 17, 0));
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double duration = config_.frames / config_.frame_rate_hz;
  int k = 0;
  for (double t = 8.0; t < duration; t += 25.0, ++k) {
    const VehiclePose at = scene_->vehicleAt(t + 4.0 + 2.0 * unit(rng));
    const Eigen::Vector2d normal(-std::sin(at.yaw_rad), std::cos(at.yaw_rad));
    const Eigen::Vector2d xy = at.xy + (unit(rng) < 0.5 ? -1.0 : 1.0) * (5.0 + 6.0 * unit(rng)) * normal;
    const double yaw = at.yaw_rad + (unit(rng) - 0.5) * M_PI;
    const int id = kConfounderIdBase + 2 * k;
    if (k % 2 == 0) {
      confounders_.push_back({makeParkedVehicle(xy, yaw, false), id, 95.0});
      confounders_.push_back({makeParkedVehicle(xy, yaw, true), id + 1, 300.0});  // ~325 K: above the band
    } else {
      confounders_.push_back({makeAnimal(xy, yaw), id, 190.0 + 15.0 * unit(rng)});  // in the band
    }
  }
}

void SyntheticRig::drawChange() {
  const ExtrinsicChangeConfig& c = config_.extrinsic_change;
  change_ = ExtrinsicChange{};
  change_.before = change_.after = config_.rig.truth;
  if (!c.enabled()) return;
  // Its own stream: the rest of the drive is the same with and without the change.
  std::mt19937_64 rng(mixSeed(config_.seed, 13, 0));
  std::normal_distribution<double> gauss(0.0, 1.0);
  auto randomUnit = [&]() {
    Eigen::Vector3d v;
    do {
      v = Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng));
    } while (v.norm() < 1e-6);
    return Eigen::Vector3d(v.normalized());
  };
  change_.enabled = true;
  change_.at_s = c.at_s;
  change_.at_stamp_s = config_.start_stamp_s + c.at_s;
  // Frame i is at start + i / rate: the first at or after the change (tolerating rounding).
  change_.first_frame = static_cast<int>(std::ceil(c.at_s * config_.frame_rate_hz - 1e-9));
  change_.rotation_deg = c.rotation_deg;
  change_.translation_cm = c.translation_cm;
  change_.axis = randomUnit();
  change_.translation_direction = randomUnit();
  change_.after = bumpedExtrinsic(config_.rig.truth, change_.axis, c.rotation_deg,
                                  0.01 * c.translation_cm * change_.translation_direction);
  renderer_after_ = std::make_unique<ThermalRenderer>(config_.rig.camera, change_.after, groundZ());
}

const Extrinsic& SyntheticRig::truthAt(int index) const {
  return change_.enabled && index >= change_.first_frame ? change_.after : change_.before;
}

const ThermalRenderer& SyntheticRig::rendererAt(int index) const {
  return change_.enabled && index >= change_.first_frame ? *renderer_after_ : *renderer_;
}

ColumnRange SyntheticRig::emptyColumns() const {
  return regionColumns(config_.empty_image_region, config_.rig.camera.width);
}

SyntheticFrame SyntheticRig::render(int index) const { return renderWorld(frameWorld(index), index, stampOf(index)); }

SyntheticFrame SyntheticRig::renderSnapshot(const std::vector<WorldObject>& objects, int index,
                                            double stamp_s) const {
  FrameWorld world;
  world.objects = objects;
  world.camera_count = objects.size();
  world.lidar = objects;
  for (std::size_t j = 0; j < objects.size(); ++j) world.lidar_object.push_back(static_cast<int>(j));
  return renderWorld(world, index, stamp_s);
}

SyntheticRig::Observation SyntheticRig::observe(const FrameWorld& world, int index) const {
  Observation seen;
  if (world.lidar_refs.empty()) {
    seen.returns = castLidarScan(config_.rig.lidar, world.lidar, groundZ());
    for (auto& r : seen.returns) {
      if (r.object >= 0) r.object = world.lidar_object[static_cast<std::size_t>(r.object)];
    }
  } else {
    seen.returns = castSweptScan(world);
    seen.time_s.reserve(seen.returns.size());
    for (const auto& r : seen.returns) seen.time_s.push_back(static_cast<float>(sweep_->timeFromStamp(r.azimuth)));
  }
  if (world.camera_count == world.objects.size()) {
    seen.owners = rendererAt(index).renderOwners(world.objects);
  } else {
    const std::vector<WorldObject> camera(world.objects.begin(),
                                          world.objects.begin() + static_cast<std::ptrdiff_t>(world.camera_count));
    seen.owners = rendererAt(index).renderOwners(camera);
  }
  return seen;
}

bool SyntheticRig::projectsIntoEmptyRegion(const Eigen::Vector3f& point_lidar, int index, int margin_px) const {
  const ColumnRange columns = emptyColumns();
  const Extrinsic& truth = truthAt(index);
  const Eigen::Vector3d pc = truth.rotationMatrix() * point_lidar.cast<double>() + truth.translation;
  if (pc.z() <= 0.0) return false;
  const CameraModel& camera = config_.rig.camera;
  const Eigen::Vector2d px = camera.project(pc);
  if (px.y() < -margin_px || px.y() > camera.height - 1 + margin_px) return false;
  return px.x() >= columns.begin - margin_px - 0.5 && px.x() < columns.end + margin_px - 0.5;
}

SyntheticFrame SyntheticRig::renderWorld(const FrameWorld& world, int index, double stamp_s) const {
  // Three random streams of the frame's own; the steps below draw from them in this order.
  std::mt19937_64 rng_detect(mixSeed(config_.seed, 1, static_cast<std::uint64_t>(index)));
  std::mt19937_64 rng_noise(mixSeed(config_.seed, 2, static_cast<std::uint64_t>(index)));
  std::mt19937_64 rng_image(mixSeed(config_.seed, 3, static_cast<std::uint64_t>(index)));

  SyntheticFrame frame;
  frame.index = index;
  frame.stamp_s = stamp_s;

  // LiDAR scan with range noise along each ray; the camera's nearest object per pixel.
  Observation seen = observe(world, index);
  addRangeNoise(config_.noise.range_sigma_m, rng_noise, &seen.returns);
  const Detected detected = detect(world, seen, index, rng_detect, &frame);

  const std::vector<WorldObject>& objects = world.objects;
  const bool point_times = config_.timing.lidar_point_time;
  for (std::size_t i = 0; i < seen.returns.size(); ++i) {
    const LidarReturn& r = seen.returns[i];
    if (r.object < 0 || !detected.in_cluster[static_cast<std::size_t>(r.object)]) continue;
    const WorldObject& obj = objects[static_cast<std::size_t>(r.object)];
    frame.cluster_points.push_back(r.point);
    frame.cluster_labels.push_back(obj.isPerson() ? obj.person_id : kFalseClusterLabelBase + obj.clutter_id);
    if (point_times) frame.cluster_time_s.push_back(seen.time_s[i]);
  }

  drawMask(objects, seen.owners, detected.in_mask, rng_noise, &frame);
  // Counted as the ingest path counts them: a single-id mask split in two (a person cut by a
  // post) is two people to the consumer, so it is two here too.
  frame.counts = countPeople(frame.mask, frame.cluster_labels);

  const double drift = 3.0 * std::sin(0.05 * stamp_s);
  frame.image = rendererAt(index).renderImage(seen.owners, objects, config_.image_depth, config_.noise.image_noise,
                                              drift, rng_image);
  if (config_.raw) {
    writeRawCloud(objects, seen, &frame);
  } else if (config_.full_cloud) {
    writeFullCloud(objects, seen, &frame);
  }
  return frame;
}

SyntheticRig::Detected SyntheticRig::detect(const FrameWorld& world, const Observation& seen, int index,
                                            std::mt19937_64& rng, SyntheticFrame* frame) const {
  const std::vector<WorldObject>& objects = world.objects;
  const NoiseConfig& noise = config_.noise;
  const DetectorConfig& det = config_.detector;
  std::vector<int> hits(objects.size(), 0);
  for (const auto& r : seen.returns) {
    if (r.object >= 0) ++hits[static_cast<std::size_t>(r.object)];
  }
  std::vector<int> pixels(objects.size(), 0);
  for (int v = 0; v < seen.owners.rows; ++v) {
    const int* own = seen.owners.ptr<int>(v);
    for (int u = 0; u < seen.owners.cols; ++u) {
      if (own[u] >= 0) ++pixels[static_cast<std::size_t>(own[u])];
    }
  }

  // Each detector's range is judged where its sensor saw the object (the LiDAR's at the stamp).
  const double kNowhere = std::numeric_limits<double>::infinity();
  std::vector<double> lidar_distance(objects.size(), kNowhere), camera_distance(objects.size(), kNowhere);
  for (std::size_t k = 0; k < world.lidar.size(); ++k) {
    lidar_distance[static_cast<std::size_t>(world.lidar_object[k])] =
        world.lidar[k].solid.boundingCentre().head<2>().norm();
  }
  for (std::size_t j = 0; j < world.camera_count; ++j) {
    camera_distance[j] = objects[j].solid.boundingCentre().head<2>().norm();
  }

  // Both random draws are made for every candidate so outcomes stay aligned.
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Detected out;
  out.in_cluster.assign(objects.size(), 0);
  out.in_mask.assign(objects.size(), 0);
  std::vector<char>& in_cluster = out.in_cluster;
  for (std::size_t j = 0; j < objects.size(); ++j) {
    const double u_cluster = unit(rng);
    const double u_mask = unit(rng);
    const bool lidar_in_range = lidar_distance[j] <= det.detection_range_m;
    const bool camera_in_range = camera_distance[j] <= det.detection_range_m;
    if (!lidar_in_range && !camera_in_range) continue;
    if (objects[j].isPerson()) {
      in_cluster[j] = lidar_in_range && hits[j] >= det.min_cluster_points && u_cluster >= noise.miss_rate;
      out.in_mask[j] = camera_in_range && pixels[j] >= det.min_mask_pixels && u_mask >= noise.miss_rate;
      PersonInFrame p;
      p.person_id = objects[j].person_id;
      p.distance_m = lidar_in_range ? lidar_distance[j] : camera_distance[j];
      p.lidar_hits = hits[j];
      p.visible_pixels = pixels[j];
      p.in_cluster = in_cluster[j] != 0;
      frame->people.push_back(p);
    } else {
      in_cluster[j] = lidar_in_range && hits[j] >= det.min_cluster_points && u_cluster < noise.false_cluster_rate;
    }
  }
  if (config_.empty_image_region != ImageRegion::kNone) {
    // Nobody is reported in the empty region: not even a post mistaken for a person.
    for (const auto& r : seen.returns) {
      if (r.object >= 0 && in_cluster[r.object] && !objects[r.object].isPerson() &&
          projectsIntoEmptyRegion(r.point, index, 0)) {
        in_cluster[r.object] = 0;
      }
    }
  }
  return out;
}

void SyntheticRig::drawMask(const std::vector<WorldObject>& objects, const cv::Mat& owners,
                            const std::vector<char>& in_mask, std::mt19937_64& rng, SyntheticFrame* frame) const {
  // Ids 1..N by increasing person id.
  std::vector<int> mask_id(objects.size(), 0);
  std::map<int, std::size_t> by_person;
  for (std::size_t j = 0; j < objects.size(); ++j) {
    if (in_mask[j]) by_person[objects[j].person_id] = j;
  }
  int next_id = 1;
  for (const auto& kv : by_person) mask_id[kv.second] = next_id++;
  for (auto& p : frame->people) {
    for (std::size_t j = 0; j < objects.size(); ++j) {
      if (objects[j].person_id == p.person_id) p.mask_id = mask_id[j];
    }
  }
  frame->mask = cv::Mat::zeros(owners.rows, owners.cols, CV_8UC1);
  for (int v = 0; v < owners.rows; ++v) {
    const int* own = owners.ptr<int>(v);
    std::uint8_t* m = frame->mask.ptr<std::uint8_t>(v);
    for (int u = 0; u < owners.cols; ++u) {
      if (own[u] >= 0) m[u] = static_cast<std::uint8_t>(mask_id[static_cast<std::size_t>(own[u])]);
    }
  }
  const NoiseConfig& noise = config_.noise;
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  perturbMaskEdges(frame->mask, noise.mask_edge_px, rng, noise.mask_edge_sign, noise.mask_erosion_part);
  if (unit(rng) < noise.false_mask_rate) addFalseMaskBlob(frame->mask, next_id, rng);
  const ColumnRange empty = emptyColumns();
  if (empty.end > empty.begin) {  // edge noise and false blobs stay out of the empty region too
    frame->mask.colRange(empty.begin, empty.end).setTo(0);
  }
  if (config_.mask_style == MaskStyle::kBinary) frame->mask.setTo(255, frame->mask != 0);
}

void SyntheticRig::writeRawCloud(const std::vector<WorldObject>& objects, const Observation& seen,
                                 SyntheticFrame* frame) const {
  const cv::Mat& owners = seen.owners;
  frame->truth_person_ids = cv::Mat::zeros(owners.rows, owners.cols, CV_16UC1);
  for (int v = 0; v < owners.rows; ++v) {
    const int* own = owners.ptr<int>(v);
    std::uint16_t* id = frame->truth_person_ids.ptr<std::uint16_t>(v);
    for (int u = 0; u < owners.cols; ++u) {
      if (own[u] >= 0) id[u] = static_cast<std::uint16_t>(objects[static_cast<std::size_t>(own[u])].person_id);
    }
  }
  const bool point_times = config_.timing.lidar_point_time;
  for (std::size_t i = 0; i < seen.returns.size(); ++i) {
    const LidarReturn& r = seen.returns[i];
    if (r.range_m > config_.raw_cloud_max_range_m) continue;
    frame->full_points.push_back(r.point);
    if (point_times) frame->full_time_s.push_back(seen.time_s[i]);
    float intensity = 15.f + static_cast<float>(r.beam % 4);
    std::uint32_t truth_id = 0;
    if (r.object >= 0) {
      const WorldObject& obj = objects[static_cast<std::size_t>(r.object)];
      intensity = obj.isPerson() ? 80.f : 45.f;
      truth_id = obj.isPerson() ? static_cast<std::uint32_t>(obj.person_id) : 0u;
    }
    frame->full_intensity.push_back(intensity);
    frame->full_ring.push_back(static_cast<std::uint16_t>(r.beam));
    frame->full_truth_id.push_back(truth_id);
  }
}

void SyntheticRig::writeFullCloud(const std::vector<WorldObject>& objects, const Observation& seen,
                                  SyntheticFrame* frame) const {
  const bool point_times = config_.timing.lidar_point_time;
  for (std::size_t i = 0; i < seen.returns.size(); ++i) {
    const LidarReturn& r = seen.returns[i];
    if (r.azimuth % config_.full_cloud_azimuth_step != 0 || r.range_m > config_.full_cloud_max_range_m) continue;
    if (r.object < 0 && r.beam % 2 != 0) continue;  // ground: every second beam is plenty
    frame->full_points.push_back(r.point);
    if (point_times) frame->full_time_s.push_back(seen.time_s[i]);
    float intensity = 15.f + static_cast<float>(r.beam % 4);
    if (r.object >= 0) intensity = objects[static_cast<std::size_t>(r.object)].isPerson() ? 80.f : 45.f;
    frame->full_intensity.push_back(intensity);
  }
}

RejectionCounts gateFrames(const std::vector<PeopleCounts>& frames, const GateConfig& gate_config) {
  FrameGate gate(gate_config);
  for (const PeopleCounts& counts : frames) {
    if (gate.consumeSkip()) continue;
    gate.decide(counts.mask_people, counts.cluster_people, counts.smallest_cluster_points);
  }
  return gate.counts();
}

}  // namespace synthetic
}  // namespace thermal_lidar_calibration
