// The generator options other issues test against: a mid-drive extrinsic change (drift, #9) and
// an image third nobody is seen in (coverage, #8).
#include "thermal_lidar_calibration/core/extrinsic.hpp"
#include "thermal_lidar_calibration/synthetic/synthetic_rig.hpp"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include <cmath>

namespace tlc = thermal_lidar_calibration;
namespace syn = thermal_lidar_calibration::synthetic;

namespace {

constexpr double kRadToDeg = 180.0 / M_PI;

syn::SyntheticConfig driftConfig(std::uint64_t seed) {
  syn::SyntheticConfig config;
  config.frames = 300;
  config.seed = seed;
  config.extrinsic_change.at_s = 12.35;  // between frames 123 and 124
  config.extrinsic_change.rotation_deg = 0.5;
  config.extrinsic_change.translation_cm = 3.0;
  return config;
}

// Mean L1 distance (px) from the clean clusters, projected with `extrinsic`, to the mask.
double meanDistanceToMask(const syn::SyntheticFrame& frame, const syn::RigPreset& rig, const tlc::Extrinsic& e,
                          int* points) {
  cv::Mat dist;
  cv::distanceTransform(frame.mask == 0, dist, cv::DIST_L1, 3);
  const Eigen::Matrix3d R = e.rotationMatrix();
  double sum = 0.0;
  *points = 0;
  for (const auto& p : frame.cluster_points) {
    const Eigen::Vector3d pc = R * p.cast<double>() + e.translation;
    if (pc.z() <= 0.0) continue;
    const Eigen::Vector2d px = rig.camera.project(pc);
    const int u = static_cast<int>(std::lround(px.x())), v = static_cast<int>(std::lround(px.y()));
    if (u < 0 || v < 0 || u >= rig.camera.width || v >= rig.camera.height) continue;
    sum += dist.at<float>(v, u);
    ++*points;
  }
  return *points > 0 ? sum / *points : 0.0;
}

}  // namespace

TEST(SyntheticDrift, TheChangeHasTheRequestedSizeAndIsDrawnFromTheSeed) {
  const syn::SyntheticRig rig(driftConfig(3));
  const syn::ExtrinsicChange& change = rig.extrinsicChange();
  ASSERT_TRUE(change.enabled);
  EXPECT_EQ(change.first_frame, 124);
  EXPECT_DOUBLE_EQ(change.at_stamp_s, rig.config().start_stamp_s + 12.35);
  EXPECT_NEAR(tlc::rotationErrorRad(change.before, change.after) * kRadToDeg, 0.5, 1e-9);
  EXPECT_NEAR(tlc::translationErrorM(change.before, change.after), 0.03, 1e-12);
  EXPECT_NEAR(change.axis.norm(), 1.0, 1e-12);
  // The bump turns about `axis` in the camera frame: R_after R_before^T is that rotation.
  const Eigen::AngleAxisd bump(change.after.rotationMatrix() * change.before.rotationMatrix().transpose());
  EXPECT_NEAR(bump.axis().dot(change.axis), 1.0, 1e-6);
  EXPECT_TRUE(change.before.translation.isApprox(rig.config().rig.truth.translation));
  // In force: before up to frame 123, after from frame 124 on.
  EXPECT_TRUE(rig.truthAt(123).rotation_vector.isApprox(change.before.rotation_vector));
  EXPECT_TRUE(rig.truthAt(124).rotation_vector.isApprox(change.after.rotation_vector));
  // Deterministic per seed, different across seeds.
  const syn::SyntheticRig same(driftConfig(3)), other(driftConfig(4));
  EXPECT_EQ(same.extrinsicChange().axis, change.axis);
  EXPECT_GT((other.extrinsicChange().axis - change.axis).norm(), 1e-3);
}

TEST(SyntheticDrift, FramesBeforeTheChangeAreUnchangedAndAfterItFollowTheNewExtrinsic) {
  const syn::SyntheticConfig config = driftConfig(1);
  syn::SyntheticConfig stable_config = config;
  stable_config.extrinsic_change = {};
  const syn::SyntheticRig rig(config), stable(stable_config);
  // Before the change: identical to a drive without it.
  for (int i : {0, 60, 123}) {
    const syn::SyntheticFrame a = rig.render(i), b = stable.render(i);
    EXPECT_EQ(cv::norm(a.image, b.image, cv::NORM_INF), 0.0) << i;
    EXPECT_EQ(cv::norm(a.mask, b.mask, cv::NORM_INF), 0.0) << i;
    EXPECT_EQ(a.cluster_points, b.cluster_points) << i;
  }
  // After it: the clusters (the LiDAR did not move) lie on the mask under the new extrinsic, not
  // under the old one (0.5 deg is ~6.7 px at this focal length).
  double sum_after = 0.0, sum_before = 0.0;
  int points = 0;
  for (int i = 124; i < config.frames; i += 5) {
    const syn::SyntheticFrame frame = rig.render(i);
    EXPECT_EQ(frame.cluster_points, stable.render(i).cluster_points) << i;
    if (frame.counts.mask_people != frame.counts.cluster_people || frame.counts.mask_people == 0) continue;
    int n = 0;
    sum_after += meanDistanceToMask(frame, config.rig, rig.extrinsicChange().after, &n) * n;
    sum_before += meanDistanceToMask(frame, config.rig, rig.extrinsicChange().before, &n) * n;
    points += n;
  }
  ASSERT_GT(points, 100);
  EXPECT_LT(sum_after / points, 0.25);
  EXPECT_GT(sum_before / points, 1.0);
}

TEST(SyntheticDrift, BadChangesAreRefused) {
  syn::SyntheticConfig config = driftConfig(1);
  config.extrinsic_change.at_s = 30.0;  // the drive is 30 s long
  EXPECT_THROW(syn::SyntheticRig{config}, std::invalid_argument);
  config.extrinsic_change.at_s = 10.0;
  config.extrinsic_change.rotation_deg = 0.0;
  config.extrinsic_change.translation_cm = 0.0;
  EXPECT_THROW(syn::SyntheticRig{config}, std::invalid_argument);
  config.extrinsic_change.rotation_deg = 50.0;
  EXPECT_THROW(syn::SyntheticRig{config}, std::invalid_argument);
}

TEST(SyntheticRegion, ColumnsAreTheThirdsOfTheWidth) {
  const syn::ColumnRange left = syn::regionColumns(syn::ImageRegion::kLeft, 640);
  const syn::ColumnRange centre = syn::regionColumns(syn::ImageRegion::kCentre, 640);
  const syn::ColumnRange right = syn::regionColumns(syn::ImageRegion::kRight, 640);
  EXPECT_EQ(left.begin, 0);
  EXPECT_EQ(left.end, centre.begin);
  EXPECT_EQ(centre.end, right.begin);
  EXPECT_EQ(right.end, 640);
  for (int u = 0; u < 640; ++u) {
    const int k = u * 3 / 640;
    EXPECT_EQ(left.contains(u), k == 0) << u;
    EXPECT_EQ(centre.contains(u), k == 1) << u;
    EXPECT_EQ(right.contains(u), k == 2) << u;
  }
  EXPECT_EQ(syn::imageRegionByName("centre"), syn::ImageRegion::kCentre);
  EXPECT_THROW(syn::imageRegionByName("center"), std::invalid_argument);
}

// Nobody in the region: no mask pixel, no cluster point projecting there, even with every
// clutter object reported as a person and a false blob in every mask; people elsewhere remain.
TEST(SyntheticRegion, NothingIsReportedInTheEmptyThird) {
  for (const syn::ImageRegion region : {syn::ImageRegion::kLeft, syn::ImageRegion::kCentre, syn::ImageRegion::kRight}) {
    syn::SyntheticConfig config;
    config.frames = 240;
    config.seed = 1;
    config.noise = syn::NoiseConfig::realistic();
    config.noise.false_cluster_rate = 1.0;
    config.noise.false_mask_rate = 1.0;
    config.empty_image_region = region;
    const syn::SyntheticRig rig(config);
    const syn::ColumnRange columns = rig.emptyColumns();
    ASSERT_LT(columns.begin, columns.end);
    int frames_with_people = 0, cluster_points_in_view = 0;
    for (int i = 0; i < config.frames; i += 4) {
      const syn::SyntheticFrame frame = rig.render(i);
      EXPECT_EQ(cv::countNonZero(frame.mask.colRange(columns.begin, columns.end)), 0)
          << syn::toString(region) << " frame " << i;
      const Eigen::Matrix3d R = rig.truthAt(i).rotationMatrix();
      for (const auto& p : frame.cluster_points) {
        const Eigen::Vector3d pc = R * p.cast<double>() + rig.truthAt(i).translation;
        if (pc.z() <= 0.0) continue;
        const Eigen::Vector2d px = config.rig.camera.project(pc);
        if (px.y() < -0.5 || px.y() >= config.rig.camera.height - 0.5) continue;
        const int u = static_cast<int>(std::lround(px.x()));
        if (u >= 0 && u < config.rig.camera.width) ++cluster_points_in_view;
        EXPECT_FALSE(columns.contains(u)) << syn::toString(region) << " frame " << i;
      }
      frames_with_people += frame.counts.mask_people > 0;
    }
    EXPECT_GT(frames_with_people, 5) << syn::toString(region);
    EXPECT_GT(cluster_points_in_view, 100) << syn::toString(region);
  }
}

// The centre keeps people on both sides of the path, so the world is the same as without the
// option: where the unrestricted drive shows someone in the centre third (seed 1 starts with a
// group ahead, seen there), the restricted one has left them out of that frame, both sensors.
TEST(SyntheticRegion, PeopleWhoWouldShowThereAreLeftOutOfTheFrame) {
  syn::SyntheticConfig config;  // the demo drive (the path depends on its length)
  config.seed = 1;
  const syn::SyntheticRig unrestricted(config);
  config.empty_image_region = syn::ImageRegion::kCentre;
  const syn::SyntheticRig rig(config);
  const syn::ColumnRange centre = rig.emptyColumns();
  int compared = 0;
  for (int i = 0; i < 50; i += 7) {
    const syn::SyntheticFrame before = unrestricted.render(i), after = rig.render(i);
    ASSERT_GT(cv::countNonZero(before.mask.colRange(centre.begin, centre.end)), 0) << "frame " << i;
    EXPECT_EQ(cv::countNonZero(after.mask.colRange(centre.begin, centre.end)), 0) << "frame " << i;
    // Left out of the world, not only of the mask: fewer LiDAR points on people too.
    EXPECT_LT(after.cluster_points.size(), before.cluster_points.size()) << "frame " << i;
    EXPECT_LT(rig.snapshot(i).size(), unrestricted.snapshot(i).size()) << "frame " << i;
    ++compared;
  }
  EXPECT_EQ(compared, 8);
}
