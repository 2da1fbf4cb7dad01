#pragma once
// Renders the frames of a synthetic drive: LiDAR scan, person clusters, thermal image and person
// mask, with the detector behaviour and noise of the configuration. ROS-free; frame i depends
// only on (seed, i), so frames can be rendered in any order or in parallel. Each sensor sees the
// world at its own instants (SensorTimingConfig): by default both at the frame's stamp.

#include "thermal_lidar_calibration/core/frame_gate.hpp"
#include "thermal_lidar_calibration/core/person_counter.hpp"
#include "thermal_lidar_calibration/core/extrinsic.hpp"
#include "thermal_lidar_calibration/synthetic/image_region.hpp"
#include "thermal_lidar_calibration/synthetic/lidar_scanner.hpp"
#include "thermal_lidar_calibration/synthetic/noise_model.hpp"
#include "thermal_lidar_calibration/synthetic/rig_presets.hpp"
#include "thermal_lidar_calibration/synthetic/scene.hpp"
#include "thermal_lidar_calibration/synthetic/sensor_timing.hpp"
#include "thermal_lidar_calibration/synthetic/thermal_renderer.hpp"
#include "thermal_lidar_calibration/synthetic/world_object.hpp"

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include <cstdint>
#include <memory>
#include <random>
#include <vector>

namespace thermal_lidar_calibration {
namespace synthetic {

enum class MaskStyle : std::uint8_t { kIds, kBinary };

// What the stand-in person detectors report.
struct DetectorConfig {
  double detection_range_m = 30.0;  // horizontal distance LiDAR-person for either modality
  int min_cluster_points = 5;       // LiDAR detector needs at least this many hits
  int min_mask_pixels = 40;         // segmentation needs at least this many visible pixels
};

// A bump mid-drive (issue #9): from drive time at_s on, the camera is turned by rotation_deg
// about a random axis and shifted by translation_cm in a random direction (both drawn from the
// seed, both in the camera frame): R_after = Rot(axis, rotation_deg) R, t_after = t + shift.
// So rotationErrorRad(before, after) = rotation_deg and translationErrorM = translation_cm.
struct ExtrinsicChangeConfig {
  double at_s = -1.0;  // seconds from the start of the drive; < 0: no change
  double rotation_deg = 0.0;
  double translation_cm = 0.0;
  bool enabled() const { return at_s >= 0.0; }
};

// `e` after a bump: turned by `degrees` about `axis` (any length) and shifted by `shift_m`, both
// in the camera frame: R' = Rot(axis, degrees) R, t' = t + shift_m.
Extrinsic bumpedExtrinsic(const Extrinsic& e, const Eigen::Vector3d& axis, double degrees,
                          const Eigen::Vector3d& shift_m);

// The change as drawn for this seed.
struct ExtrinsicChange {
  bool enabled = false;
  double at_s = 0.0;
  double at_stamp_s = 0.0;        // start_stamp_s + at_s
  int first_frame = 0;            // first frame index whose stamp is >= at_stamp_s
  double rotation_deg = 0.0;
  double translation_cm = 0.0;
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();                   // unit, camera frame
  Eigen::Vector3d translation_direction = Eigen::Vector3d::UnitX();  // unit, camera frame
  Extrinsic before, after;
};

struct SyntheticConfig {
  RigPreset rig = fieldsafeRig();
  SceneConfig scene;                 // duration_s and speed_mps are overwritten from frames/rig
  NoiseConfig noise;
  DetectorConfig detector;
  int frames = 1200;                 // ~60-75 gated pairs with the FieldSAFE-like rig
  double frame_rate_hz = 10.0;
  double start_stamp_s = 1.6e9;      // stamp of frame 0
  std::uint64_t seed = 1;
  MaskStyle mask_style = MaskStyle::kIds;
  ImageDepth image_depth = ImageDepth::kMono8;
  bool full_cloud = false;
  int full_cloud_azimuth_step = 8;   // full cloud: every n-th azimuth, every 2nd ground beam,
  double full_cloud_max_range_m = 30.0;  // and nothing farther (keeps bags small)
  // Raw sensor data for the person detectors (make_synthetic_bag --raw): the full cloud at full
  // density (every azimuth and beam, to raw_cloud_max_range_m) with ring and truth ids, and a
  // radiometric mono16 image (kelvin = counts * kRawKelvinPerCount) from a temperature model:
  // people at body-surface temperatures, sun-heated posts as warm confounders, cool ground,
  // cold sky.
  bool raw = false;
  double raw_cloud_max_range_m = 40.0;
  ExtrinsicChangeConfig extrinsic_change;
  // Nobody is ever seen in this third of the image: people stand on the other side of the path
  // (left/right), and in a frame where a person would show there (pixels or LiDAR points within
  // 2 px) they are not in that frame's world at all; nor are false clusters or mask blobs there.
  ImageRegion empty_image_region = ImageRegion::kNone;
  // Issue 21: the camera's offset from its stamps, the LiDAR's sweep and stamp convention. The
  // speed profile is scene.speed_profile.
  SensorTimingConfig timing;
  void validate() const;  // throws std::invalid_argument
};

// Ground truth about one person in one frame.
struct PersonInFrame {
  int person_id = 0;
  double distance_m = 0.0;  // horizontal, from the LiDAR
  int lidar_hits = 0;
  int visible_pixels = 0;
  bool in_cluster = false;  // reported by the LiDAR detector
  int mask_id = 0;          // value in the mask, 0 = not reported
};

struct SyntheticFrame {
  int index = 0;
  double stamp_s = 0.0;
  cv::Mat image;  // CV_8UC1 or CV_16UC1
  cv::Mat mask;   // CV_8UC1: 0 background, ids 1..N (or 255 for the binary style)
  std::vector<Eigen::Vector3f> cluster_points;  // LiDAR frame
  std::vector<std::int32_t> cluster_labels;     // person id (false clusters: 1000 + clutter id)
  std::vector<Eigen::Vector3f> full_points;     // optional decimated full scan
  std::vector<float> full_intensity;
  std::vector<std::uint16_t> full_ring;        // with `raw`: the beam of each full point
  std::vector<std::uint32_t> full_truth_id;    // with `raw`: person id of each point, 0 = none
  // With timing.lidar_point_time: each point's capture time minus the stamp, s (velodyne's `time`).
  std::vector<float> cluster_time_s;
  std::vector<float> full_time_s;
  cv::Mat truth_person_ids;  // with `raw`: CV_16UC1, the person id each pixel shows (0 = none), every
                             // person rendered, at any range (the ideal mask holds only detectable ones)
  PeopleCounts counts;     // as the ingest path counts them (core countPeople)
  std::vector<PersonInFrame> people;  // every person within detection range
};

// A person's place and motion relative to the LiDAR at one instant: what the camera sees change
// (the vehicle's translation and turning, and the person's walk), for comparing estimates with.
struct PersonMotion {
  int person_id = 0;
  // The body's vertical axis at half its height, in the LiDAR frame of that instant, m.
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();
  // d/dt of position_m as seen in the moving LiDAR frame: R^T (v_person - v_vehicle) - w x p.
  Eigen::Vector3d velocity_mps = Eigen::Vector3d::Zero();
};

class SyntheticRig {
 public:
  explicit SyntheticRig(const SyntheticConfig& config);

  SyntheticFrame render(int index) const;
  // Lower level: one frame from an explicit world snapshot (objects in the LiDAR frame), seen
  // by both sensors at once (an instantaneous scan), with the extrinsic of frame `index`.
  SyntheticFrame renderSnapshot(const std::vector<WorldObject>& objects, int index, double stamp_s) const;
  // The objects of frame `index` at its stamp in the LiDAR frame (people first, then clutter in
  // range), without the people an empty image region keeps out of that frame.
  std::vector<WorldObject> snapshot(int index) const;
  // The objects near the vehicle at any instant (`stamp_s` on the bag's clock) in the LiDAR frame
  // of that instant: what an instantaneous sensor would see then (no empty region applied).
  std::vector<WorldObject> worldAt(double stamp_s) const;
  double stampOf(int index) const { return config_.start_stamp_s + index / config_.frame_rate_hz; }

  // Person `person_id` (1-based, as the cluster labels) at `stamp_s`; throws
  // std::invalid_argument for an id the scene does not have.
  PersonMotion personMotion(int person_id, double stamp_s) const;
  // The swept scan's timing (null when scans are instantaneous).
  const LidarSweep* sweep() const { return sweep_.get(); }

  const SyntheticConfig& config() const { return config_; }
  const Scene& scene() const { return *scene_; }
  const ThermalRenderer& renderer() const { return *renderer_; }  // the extrinsic at the start
  double groundZ() const { return -config_.rig.lidar_height_m; }

  // The true extrinsic in force at frame `index` and the camera that sees with it.
  const Extrinsic& truthAt(int index) const;
  const ThermalRenderer& rendererAt(int index) const;
  const ExtrinsicChange& extrinsicChange() const { return change_; }
  // Columns no person, cluster or mask blob ever reaches (empty when no region is set).
  ColumnRange emptyColumns() const;

 private:
  // What the sensors see of a frame's world, before any noise; object indices are into
  // FrameWorld::objects.
  struct Observation {
    std::vector<LidarReturn> returns;
    std::vector<float> time_s;  // swept scans: per return, capture time minus the stamp
    cv::Mat owners;             // CV_32SC1: object index per pixel, -1 none
  };
  // One object of the world, placed at any instant by place().
  struct ObjectRef {
    enum class Kind : std::uint8_t { kPerson, kClutter, kConfounder } kind = Kind::kPerson;
    std::size_t index = 0;  // into the scene's people or clutter, or confounders_
    bool operator==(const ObjectRef& o) const { return kind == o.kind && index == o.index; }
  };
  // What each sensor sees of one frame. objects[0, camera_count) are the camera's, placed at its
  // instant; the objects only the LiDAR sees follow (placed at the scan's stamp). lidar holds
  // the LiDAR's objects at the stamp (what an instantaneous scan casts), lidar_object[k] is
  // lidar[k]'s index in objects; a swept scan places lidar_refs[k] anew per sector.
  struct FrameWorld {
    std::vector<WorldObject> objects;
    std::size_t camera_count = 0;
    std::vector<WorldObject> lidar;
    std::vector<int> lidar_object;
    std::vector<ObjectRef> lidar_refs;  // empty: the scan is instantaneous
    double scan_time_s = 0.0;           // drive time of the stamp
  };
  FrameWorld frameWorld(int index) const;
  SyntheticFrame renderWorld(const FrameWorld& world, int index, double stamp_s) const;
  // renderWorld's steps. Which objects the detectors report (and frame->people), from the
  // frame's detection stream:
  struct Detected {
    std::vector<char> in_cluster, in_mask;  // per object of the world
  };
  Detected detect(const FrameWorld& world, const Observation& seen, int index, std::mt19937_64& rng,
                  SyntheticFrame* frame) const;
  // The person mask (ids 1..N by increasing person id), its edge noise and false blobs from the
  // frame's noise stream.
  void drawMask(const std::vector<WorldObject>& objects, const cv::Mat& owners, const std::vector<char>& in_mask,
                std::mt19937_64& rng, SyntheticFrame* frame) const;
  // The whole cloud: `raw` keeps every return near enough, with ring and truth ids; `full_cloud`
  // a thinned one for display.
  void writeRawCloud(const std::vector<WorldObject>& objects, const Observation& seen, SyntheticFrame* frame) const;
  void writeFullCloud(const std::vector<WorldObject>& objects, const Observation& seen, SyntheticFrame* frame) const;
  Observation observe(const FrameWorld& world, int index) const;
  std::vector<LidarReturn> castSweptScan(const FrameWorld& world) const;
  // The objects within kWorldCullM of the vehicle at drive time t_s, people first, then clutter,
  // then the raw drive's confounders; and one of them placed at t_s in the LiDAR frame then.
  std::vector<ObjectRef> objectsNear(double t_s) const;
  WorldObject place(const ObjectRef& ref, const Eigen::Isometry3d& T_lidar_world, double t_s) const;
  Eigen::Isometry3d lidarFromWorld(double t_s) const;
  // Drops every person who would be seen (pixels or LiDAR points) in the empty region.
  void removePeopleSeenInEmptyRegion(FrameWorld& world, int index) const;
  bool projectsIntoEmptyRegion(const Eigen::Vector3f& point_lidar, int index, int margin_px) const;
  void drawChange();

  SyntheticConfig config_;
  std::unique_ptr<Scene> scene_;
  std::unique_ptr<ThermalRenderer> renderer_;
  std::unique_ptr<ThermalRenderer> renderer_after_;  // with the extrinsic after the change
  ExtrinsicChange change_;
  std::vector<double> person_grey_;
  // Raw data's warm confounders (parked vehicles with a hot engine, animals at body
  // temperature), world frame, placed beside the path by placeConfounders().
  struct Confounder {
    Solid solid;
    int id = 0;           // clutter id (from kConfounderIdBase)
    double grey_level = 0;
  };
  std::vector<Confounder> confounders_;
  void placeConfounders();
  std::unique_ptr<LidarSweep> sweep_;
};

// The decisions a consumer's gate (core FrameGate, as in DatasetBuilder) makes on frames with
// these counts, in order. With skip_frames = 0, kept = frames with equal counts in 1..max_people.
RejectionCounts gateFrames(const std::vector<PeopleCounts>& frames, const GateConfig& gate);

// Stable per-stream seed (splitmix64 of the inputs).
std::uint64_t mixSeed(std::uint64_t seed, std::uint64_t stream, std::uint64_t index);

}  // namespace synthetic
}  // namespace thermal_lidar_calibration
