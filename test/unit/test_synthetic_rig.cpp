// The synthetic rig end to end (no ROS): projection consistency of clusters and masks under the
// true extrinsic, people counts in view, determinism, presets, noise options.
#include "thermal_lidar_calibration/core/camera_model.hpp"
#include "thermal_lidar_calibration/synthetic/synthetic_rig.hpp"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>

namespace tlc = thermal_lidar_calibration;
namespace syn = thermal_lidar_calibration::synthetic;

namespace {

// Mean and max L1 distance (px) from each in-image projected cluster point to the nearest mask
// pixel; also counts points that project inside the image.
struct ProjectionStats {
  double mean_l1 = 0.0;
  double max_l1 = 0.0;
  int points = 0;
};

ProjectionStats projectionStats(const syn::SyntheticFrame& frame, const syn::RigPreset& rig) {
  ProjectionStats stats;
  cv::Mat background = frame.mask == 0;  // 255 where no person
  cv::Mat dist;
  cv::distanceTransform(background, dist, cv::DIST_L1, 3);
  const Eigen::Matrix3d R = rig.truth.rotationMatrix();
  double sum = 0.0;
  for (const auto& p : frame.cluster_points) {
    const Eigen::Vector3d pc = R * p.cast<double>() + rig.truth.translation;
    if (pc.z() <= 0.0) continue;
    const Eigen::Vector2d px = rig.camera.project(pc);
    const int u = static_cast<int>(std::lround(px.x())), v = static_cast<int>(std::lround(px.y()));
    if (u < 0 || v < 0 || u >= rig.camera.width || v >= rig.camera.height) continue;
    const double d = dist.at<float>(v, u);
    sum += d;
    stats.max_l1 = std::max(stats.max_l1, d);
    ++stats.points;
  }
  if (stats.points > 0) stats.mean_l1 = sum / stats.points;
  return stats;
}

syn::SyntheticConfig smallConfig(const std::string& rig, int frames) {
  syn::SyntheticConfig config;
  config.rig = syn::rigByName(rig);
  config.frames = frames;
  config.seed = 7;
  return config;
}

// A person standing at (x, y) in the LiDAR frame of the given rig.
syn::WorldObject personAt(const syn::SyntheticRig& rig, double x, double y, int id) {
  syn::BodyPose pose;
  pose.ground_xy = Eigen::Vector2d(x, y);
  pose.height_m = 1.75;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translate(Eigen::Vector3d(0, 0, rig.groundZ()));
  syn::WorldObject obj;
  obj.solid = syn::makePersonBody(pose).transformed(T);
  obj.person_id = id;
  obj.grey_level = 200;
  return obj;
}

}  // namespace

TEST(SyntheticRig, PixelRaysRoundTripThroughTheLensModel) {
  for (const std::string name : {"fieldsafe", "ms2"}) {
    syn::SyntheticRig rig(smallConfig(name, 1));
    EXPECT_LT(rig.renderer().maxRoundTripErrorPx(), 1e-6) << name;
  }
}

TEST(SyntheticRig, FieldsafeTruthIsARotationNearTheDatasetValues) {
  const syn::RigPreset rig = syn::fieldsafeRig();
  const Eigen::Matrix3d R = rig.truth.rotationMatrix();
  EXPECT_NEAR((R * R.transpose() - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-9);
  EXPECT_NEAR(R.determinant(), 1.0, 1e-9);
  EXPECT_NEAR(R(0, 1), -0.9994, 2e-3);
  EXPECT_NEAR(R(2, 0), 0.9672, 2e-3);
  EXPECT_NEAR(rig.truth.translation.x(), 0.443, 1e-12);
  // The optical axis in the LiDAR frame looks forward and 10-20 deg down.
  const Eigen::Vector3d axis = R.row(2).transpose();
  EXPECT_GT(axis.x(), 0.9);
  const double down_deg = -std::asin(axis.z()) * 180.0 / M_PI;
  EXPECT_GT(down_deg, 10.0);
  EXPECT_LT(down_deg, 20.0);
}

TEST(SyntheticRig, CountsPeopleInViewAndAllRound) {
  syn::SyntheticRig rig(smallConfig("fieldsafe", 1));
  // In front (in view), behind (LiDAR only), and beyond the detection range.
  const std::vector<syn::WorldObject> objects{personAt(rig, 10.0, 1.0, 3), personAt(rig, -8.0, 2.0, 5),
                                              personAt(rig, 45.0, 0.0, 9)};
  const syn::SyntheticFrame frame = rig.renderSnapshot(objects, 0, 1.6e9);
  EXPECT_EQ(frame.mask_people, 1);
  EXPECT_EQ(frame.cluster_people, 2);
  ASSERT_EQ(frame.people.size(), 2u);  // within detection range
  EXPECT_EQ(frame.people[0].mask_id, 1);
  EXPECT_EQ(frame.people[1].mask_id, 0);
  for (const auto label : frame.cluster_labels) EXPECT_TRUE(label == 3 || label == 5);
  // The far person is still warm in the thermal image though not in the mask.
  EXPECT_GT(cv::countNonZero(frame.image > 150), cv::countNonZero(frame.mask));
}

TEST(SyntheticRig, CleanClustersProjectOntoTheMask) {
  for (const std::string name : {"fieldsafe", "ms2"}) {
    syn::SyntheticConfig config = smallConfig(name, 400);
    syn::SyntheticRig rig(config);
    double sum = 0.0;
    int points = 0, frames_checked = 0;
    double worst = 0.0;
    for (int i = 0; i < config.frames; i += 7) {
      const syn::SyntheticFrame frame = rig.render(i);
      if (frame.mask_people != frame.cluster_people || frame.mask_people == 0) continue;
      const ProjectionStats s = projectionStats(frame, config.rig);
      sum += s.mean_l1 * s.points;
      points += s.points;
      worst = std::max(worst, s.max_l1);
      ++frames_checked;
    }
    ASSERT_GT(frames_checked, 5) << name;
    ASSERT_GT(points, 200) << name;
    const double mean = sum / points;
    std::printf("[%s] equal-count frames checked %d, points %d, mean L1 %.3f px, max %.1f px\n", name.c_str(),
                frames_checked, points, mean, worst);
    EXPECT_LT(mean, 0.25) << name;
    EXPECT_LE(worst, 2.0) << name;
  }
}

TEST(SyntheticRig, SameSeedSameFramesOtherSeedOtherFrames) {
  syn::SyntheticConfig config = smallConfig("fieldsafe", 200);
  config.noise = syn::NoiseConfig::realistic();
  config.full_cloud = true;
  const syn::SyntheticRig a(config), b(config);
  config.seed = 8;
  const syn::SyntheticRig c(config);
  for (int i : {0, 57, 123}) {
    const syn::SyntheticFrame fa = a.render(i), fb = b.render(i), fc = c.render(i);
    EXPECT_EQ(cv::norm(fa.image, fb.image, cv::NORM_INF), 0.0);
    EXPECT_EQ(cv::norm(fa.mask, fb.mask, cv::NORM_INF), 0.0);
    ASSERT_EQ(fa.cluster_points.size(), fb.cluster_points.size());
    for (std::size_t k = 0; k < fa.cluster_points.size(); ++k) {
      EXPECT_EQ(fa.cluster_points[k], fb.cluster_points[k]);
      EXPECT_EQ(fa.cluster_labels[k], fb.cluster_labels[k]);
    }
    EXPECT_EQ(fa.full_points.size(), fb.full_points.size());
    EXPECT_GT(cv::norm(fa.image, fc.image, cv::NORM_L1), 0.0);
  }
}

TEST(SyntheticRig, DefaultDriveYieldsAboutSixtyGatedPairs) {
  syn::SyntheticConfig config;  // the generator's defaults
  const auto start = std::chrono::steady_clock::now();
  syn::SyntheticRig rig(config);
  std::vector<int> mask_people, cluster_people;
  for (int i = 0; i < config.frames; ++i) {
    const syn::SyntheticFrame frame = rig.render(i);
    mask_people.push_back(frame.mask_people);
    cluster_people.push_back(frame.cluster_people);
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const int equal = syn::countEqualFrames(mask_people, cluster_people);
  const int kept = syn::countGatedPairs(mask_people, cluster_people, 3, 3);
  std::printf("default: %d frames, %d equal 1..3, %d kept pairs, %zu people, %.1f s\n", config.frames, equal, kept,
              rig.scene().people().size(), seconds);
  EXPECT_GE(kept, 55);
  EXPECT_LE(kept, 95);
}

TEST(SyntheticRig, NoiseOptionsChangeWhatTheyShould) {
  syn::SyntheticConfig config = smallConfig("fieldsafe", 60);
  syn::SyntheticRig clean(config);
  config.noise.range_sigma_m = 0.05;
  config.noise.mask_edge_px = 3;
  config.mask_style = syn::MaskStyle::kBinary;
  config.image_depth = syn::ImageDepth::kMono16;
  syn::SyntheticRig noisy(config);
  int compared = 0;
  for (int i = 0; i < 60; i += 3) {
    const syn::SyntheticFrame a = clean.render(i), b = noisy.render(i);
    EXPECT_EQ(b.image.type(), CV_16UC1);
    double max_v = 0;
    cv::minMaxLoc(b.mask, nullptr, &max_v);
    if (cv::countNonZero(b.mask) > 0) EXPECT_EQ(max_v, 255.0);
    if (a.cluster_points.size() == b.cluster_points.size() && !a.cluster_points.empty()) {
      double diff = 0;
      for (std::size_t k = 0; k < a.cluster_points.size(); ++k) diff += (a.cluster_points[k] - b.cluster_points[k]).norm();
      EXPECT_GT(diff / a.cluster_points.size(), 0.01);
      EXPECT_LT(diff / a.cluster_points.size(), 0.1);
      ++compared;
    }
  }
  EXPECT_GT(compared, 0);
}

TEST(SyntheticRig, PresetsAndBadConfigs) {
  EXPECT_THROW(syn::rigByName("kitti"), std::invalid_argument);
  EXPECT_THROW(syn::NoiseConfig::preset("noisy"), std::invalid_argument);
  const syn::NoiseConfig r = syn::NoiseConfig::realistic();
  EXPECT_EQ(r.mask_edge_px, 2);
  EXPECT_DOUBLE_EQ(r.range_sigma_m, 0.02);
  syn::SyntheticConfig config;
  config.frames = 0;
  EXPECT_THROW(syn::SyntheticRig{config}, std::invalid_argument);
  config.frames = 10;
  config.noise.miss_rate = 1.5;
  EXPECT_THROW(syn::SyntheticRig{config}, std::invalid_argument);
  EXPECT_EQ(syn::countGatedPairs({1, 1, 1, 1, 1, 2, 0}, {1, 1, 1, 1, 1, 2, 0}, 3, 3), 2);
  EXPECT_EQ(syn::countGatedPairs({1, 4, 2}, {1, 4, 1}, 3, 0), 1);
}
