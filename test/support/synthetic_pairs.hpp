#pragma once
// Small, fast synthetic pairs for unit tests and benchmarks (no ROS, no ray casting; the camera
// and truth come from the synthetic library's FieldSAFE-like rig, so users link it): people are
// vertical cylinders standing on the ground in the LiDAR frame; the mask is the rasterised
// projection of a dense sampling of each cylinder (so every surface point lands on the mask),
// and the LiDAR points are a sparse random subset of the side facing the sensor. The full
// ray-cast rig with beam patterns and occlusion lives in the synthetic library.

#include "thermal_lidar_calibration/core/calibration_pair.hpp"
#include "thermal_lidar_calibration/core/camera_model.hpp"
#include "thermal_lidar_calibration/core/extrinsic.hpp"
#include "thermal_lidar_calibration/core/person_counter.hpp"
#include "thermal_lidar_calibration/core/random.hpp"
#include "thermal_lidar_calibration/synthetic/rig_presets.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

namespace thermal_lidar_calibration {
namespace test_support {

// The camera and truth of the synthetic library's FieldSAFE-like rig (FieldSAFE's K and D, and
// its own LiDAR-to-thermal transform, orthonormalised). `distorted = false`: the same K with
// zero distortion.
inline CameraModel fieldsafeCamera(bool distorted = true) {
  CameraModel camera = synthetic::fieldsafeRig().camera;
  if (!distorted) camera.distortion.fill(0.0);
  return camera;
}

inline Extrinsic fieldsafeTruth() { return synthetic::fieldsafeRig().truth; }

struct SyntheticPairsOptions {
  int pairs = 30;
  int max_people = 2;
  int points_per_person = 80;
  double min_range_m = 4.0, max_range_m = 20.0;
  double ground_z_m = -1.9;  // ground height in the LiDAR frame
  std::uint64_t seed = 7;
};

inline std::vector<CalibrationPair> makeSyntheticPairs(const CameraModel& camera,
                                                       const Extrinsic& truth,
                                                       const SyntheticPairsOptions& o) {
  Rng rng(o.seed);
  const Eigen::Matrix3d R = truth.rotationMatrix();
  const Eigen::Vector3d t = truth.translation;
  std::vector<CalibrationPair> pairs;
  while (static_cast<int>(pairs.size()) < o.pairs) {
    CalibrationPair pair;
    pair.mask = cv::Mat::zeros(camera.height, camera.width, CV_8UC1);
    const int people = 1 + static_cast<int>(rng.index(static_cast<std::size_t>(o.max_people)));
    bool ok = true;
    for (int k = 0; k < people && ok; ++k) {
      // Pick a direction through the image's middle band and a range, in the LiDAR frame.
      const double range = rng.uniform(o.min_range_m, o.max_range_m);
      const double azimuth = rng.uniform(-0.33, 0.33);
      const Eigen::Vector2d c(range * std::cos(azimuth), range * std::sin(azimuth));
      const double radius = rng.uniform(0.18, 0.28), height = rng.uniform(1.55, 1.95);
      cv::Mat person = cv::Mat::zeros(camera.height, camera.width, CV_8UC1);
      const double step = 0.004;
      // The points around the cylinder, the same at every height: their sines and cosines once
      // per person instead of once per point (a fifth of the rasterising).
      std::vector<Eigen::Vector2d> around;
      for (double a = 0; a < 2 * M_PI; a += step / radius) {
        around.emplace_back(c.x() + radius * std::cos(a), c.y() + radius * std::sin(a));
      }
      int inside = 0;
      for (double z = 0; z <= height; z += step) {
        for (const Eigen::Vector2d& xy : around) {
          const Eigen::Vector3d pl(xy.x(), xy.y(), o.ground_z_m + z);
          const Eigen::Vector3d pc = R * pl + t;
          if (pc.z() <= 0.1) continue;
          const Eigen::Vector2d uv = camera.project(pc);
          const int u = static_cast<int>(std::floor(uv.x() + 0.5));
          const int v = static_cast<int>(std::floor(uv.y() + 0.5));
          if (u < 0 || v < 0 || u >= camera.width || v >= camera.height) continue;
          person.at<std::uint8_t>(v, u) = 1;
          ++inside;
        }
      }
      if (inside < 200) {
        ok = false;
        break;
      }
      cv::morphologyEx(person, person, cv::MORPH_CLOSE,
                       cv::getStructuringElement(cv::MORPH_RECT, cv::Size(3, 3)));
      pair.mask |= person;
      // Sparse points on the half of the cylinder facing the LiDAR.
      const double facing = std::atan2(-c.y(), -c.x());
      for (int i = 0; i < o.points_per_person; ++i) {
        const double a = facing + rng.uniform(-1.55, 1.55);  // to the silhouette edges
        const Eigen::Vector3d pl(c.x() + radius * std::cos(a), c.y() + radius * std::sin(a),
                                 o.ground_z_m + rng.uniform(0.0, height));
        const Eigen::Vector3d pc = R * pl + t;
        const Eigen::Vector2d uv = camera.project(pc);
        if (uv.x() < 0 || uv.y() < 0 || uv.x() > camera.width - 1 || uv.y() > camera.height - 1) {
          continue;  // the camera sees only part of this person: keep what it sees
        }
        pair.points.push_back(pl.cast<float>());
        pair.labels.push_back(k + 1);
      }
    }
    if (!ok || pair.points.size() < 10) continue;
    pair.people = people;
    pair.stamp_s = 0.1 * static_cast<double>(pairs.size());
    pairs.push_back(std::move(pair));
  }
  return pairs;
}

// The pairs' LiDAR points as a spinning LiDAR (at the LiDAR frame's origin) would see them: each
// point's height moved onto the nearest ring (its elevation a whole number of `spacing_deg`), kept
// where that ring still meets its person (between the label's lowest and highest points), so the
// masks hold every point at the truth.
inline void snapToRings(std::vector<CalibrationPair>& pairs, double spacing_deg) {
  const double spacing = spacing_deg * M_PI / 180.0;
  for (CalibrationPair& pair : pairs) {
    std::map<std::int32_t, std::pair<float, float>> extent;  // label -> lowest, highest z
    for (std::size_t i = 0; i < pair.points.size(); ++i) {
      auto found = extent.emplace(pair.labels[i], std::make_pair(pair.points[i].z(), pair.points[i].z())).first;
      found->second.first = std::min(found->second.first, pair.points[i].z());
      found->second.second = std::max(found->second.second, pair.points[i].z());
    }
    std::vector<Eigen::Vector3f> kept;
    std::vector<std::int32_t> labels;
    for (std::size_t i = 0; i < pair.points.size(); ++i) {
      Eigen::Vector3f p = pair.points[i];
      const double horizontal = std::hypot(double(p.x()), double(p.y()));
      const double z = horizontal * std::tan(std::round(std::atan2(double(p.z()), horizontal) / spacing) * spacing);
      const auto& [lowest, highest] = extent.at(pair.labels[i]);
      if (z < lowest || z > highest) continue;
      p.z() = static_cast<float>(z);
      kept.push_back(p);
      labels.push_back(pair.labels[i]);
    }
    pair.points = std::move(kept);
    pair.labels = std::move(labels);
  }
}

// A frame the count rule rejects, made of a pair: the same people plus a post the LiDAR sees and
// the camera's mask does not (a cluster more than the mask has people), held as a candidate for
// association (regions set, mask empty). The post stands 9 m ahead, `y_m` to the left (LiDAR frame).
constexpr std::int32_t kPostLabel = 99;
inline CalibrationPair asCandidateWithPost(CalibrationPair f, std::uint64_t candidate_index, double y_m) {
  f.regions = personRegions(f.mask);
  f.mask = cv::Mat();
  f.rule = PairRule::kAssociation;
  f.candidate_index = candidate_index;
  for (int k = 0; k < 30; ++k) {
    f.points.emplace_back(9.0f, static_cast<float>(y_m), static_cast<float>(-1.9 + 0.05 * k));
    f.labels.push_back(kPostLabel);
  }
  return f;
}

}  // namespace test_support
}  // namespace thermal_lidar_calibration
