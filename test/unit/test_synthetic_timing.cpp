// The synthetic rig's sensor timing (issue 21): a camera whose images show the world some time
// after (or before) their stamps, and a LiDAR that sweeps over one rotation with per-point times.
#include "thermal_lidar_calibration/synthetic/synthetic_rig.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

namespace syn = thermal_lidar_calibration::synthetic;

namespace {

syn::SyntheticConfig driveConfig(std::uint64_t seed, int frames) {
  syn::SyntheticConfig config;
  config.seed = seed;
  config.frames = frames;
  return config;
}

syn::SyntheticConfig sweptConfig(syn::LidarStamp stamp) {
  syn::SyntheticConfig config = driveConfig(5, 600);
  config.timing.lidar_stamp = stamp;
  config.timing.lidar_point_time = true;
  config.full_cloud = true;
  return config;
}

// Frames (of the first `frames`, every `step`-th) in which someone is in the mask and the clusters.
std::vector<int> framesWithPeople(const syn::SyntheticRig& rig, int frames, int step) {
  std::vector<int> out;
  for (int i = 0; i < frames; i += step) {
    const syn::SyntheticFrame f = rig.render(i);
    if (cv::countNonZero(f.mask) > 0 && !f.cluster_points.empty()) out.push_back(i);
  }
  return out;
}

Eigen::Vector3d centroidOf(const syn::SyntheticFrame& f, int label, int* count) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  *count = 0;
  for (std::size_t i = 0; i < f.cluster_points.size(); ++i) {
    if (f.cluster_labels[i] != label) continue;
    sum += f.cluster_points[i].cast<double>();
    ++*count;
  }
  return *count > 0 ? Eigen::Vector3d(sum / *count) : sum;
}

double clockwiseFromCut(double azimuth_rad, double cut_rad) {
  double turned = std::fmod(cut_rad - azimuth_rad, 2.0 * M_PI);
  return turned < 0.0 ? turned + 2.0 * M_PI : turned;
}

}  // namespace

// The image and mask of a camera 60 ms late are exactly those of an instantaneous camera 60 ms
// later, and its scan is the scan at the stamp.
TEST(SyntheticTiming, AnImageOffsetBySIsTheImageRenderedAtTPlusS) {
  const syn::SyntheticConfig base = driveConfig(5, 400);
  syn::SyntheticConfig late = base;
  late.timing.camera_time_offset_s = 0.06;
  const syn::SyntheticRig rig(base), late_rig(late);
  int compared = 0, moved = 0;
  for (const int i : framesWithPeople(late_rig, 400, 20)) {
    const syn::SyntheticFrame f = late_rig.render(i);
    const double stamp = late_rig.stampOf(i);
    const syn::SyntheticFrame later = rig.renderSnapshot(rig.worldAt(stamp + 0.06), i, stamp);
    EXPECT_EQ(cv::norm(f.image, later.image, cv::NORM_INF), 0.0) << "frame " << i;
    EXPECT_EQ(cv::norm(f.mask, later.mask, cv::NORM_INF), 0.0) << "frame " << i;
    const syn::SyntheticFrame now = rig.render(i);
    EXPECT_EQ(f.cluster_points, now.cluster_points) << "frame " << i;
    EXPECT_EQ(f.cluster_labels, now.cluster_labels) << "frame " << i;
    if (cv::norm(f.mask, now.mask, cv::NORM_INF) > 0.0) ++moved;
    ++compared;
  }
  EXPECT_GE(compared, 3);
  EXPECT_EQ(moved, compared);  // 60 ms at 2.5 m/s moves every person in the image
}

TEST(SyntheticTiming, ANegativeOffsetShowsTheWorldBeforeTheStamp) {
  const syn::SyntheticConfig base = driveConfig(5, 400);
  syn::SyntheticConfig early = base;
  early.timing.camera_time_offset_s = -0.04;
  const syn::SyntheticRig rig(base), early_rig(early);
  const std::vector<int> frames = framesWithPeople(early_rig, 400, 40);
  ASSERT_FALSE(frames.empty());
  const int i = frames.front();
  const double stamp = early_rig.stampOf(i);
  const syn::SyntheticFrame earlier = rig.renderSnapshot(rig.worldAt(stamp - 0.04), i, stamp);
  EXPECT_EQ(cv::norm(early_rig.render(i).mask, earlier.mask, cv::NORM_INF), 0.0);
}

// Every point's time is its azimuth's place in a clockwise sweep from the cut (behind the vehicle),
// within one rotation ending at the stamp (end) or starting at it (start).
TEST(SyntheticTiming, PointTimesFollowTheAzimuthWithinOneSweep) {
  for (const syn::LidarStamp stamp : {syn::LidarStamp::kEnd, syn::LidarStamp::kStart}) {
    const syn::SyntheticRig rig(sweptConfig(stamp));
    const syn::LidarSweep& sweep = *rig.sweep();
    const double period = rig.config().timing.lidar_period_s;
    const double firing = period / rig.config().rig.lidar.azimuth_count;
    const syn::SyntheticFrame f = rig.render(100);
    ASSERT_EQ(f.full_time_s.size(), f.full_points.size());
    ASSERT_EQ(f.cluster_time_s.size(), f.cluster_points.size());
    ASSERT_GT(f.full_points.size(), 1000u);
    const double first = stamp == syn::LidarStamp::kEnd ? -period + firing : 0.0;
    std::vector<std::pair<double, float>> by_sweep;  // (angle swept from the cut, time)
    for (std::size_t i = 0; i < f.full_points.size(); ++i) {
      const float t = f.full_time_s[i];
      EXPECT_GE(t, first - 1e-6);
      EXPECT_LE(t, first + period - firing + 1e-6);
      const double azimuth = std::atan2(f.full_points[i].y(), f.full_points[i].x());
      const double swept = clockwiseFromCut(azimuth, M_PI);
      if (swept < 1e-3 || swept > 2.0 * M_PI - 1e-3) continue;  // at the cut itself: either end
      EXPECT_NEAR(t, first + swept / (2.0 * M_PI) * period, 1e-6);
      by_sweep.emplace_back(swept, t);
    }
    std::sort(by_sweep.begin(), by_sweep.end());
    for (std::size_t i = 1; i < by_sweep.size(); ++i) EXPECT_LE(by_sweep[i - 1].second, by_sweep[i].second);
    // The camera looks forward: its view is swept mid-rotation, 50 ms from either stamp.
    const double axis_time = sweep.timeFromStampAt(0.0);
    EXPECT_NEAR(axis_time, stamp == syn::LidarStamp::kEnd ? -0.05 : 0.05, 0.001);
  }
}

// A swept scan is not motion-compensated: a person's points lie where the person was, relative
// to the LiDAR, when the head passed them, not where they were at the stamp.
TEST(SyntheticTiming, SweptPointsShowTheWorldAtTheirOwnTime) {
  const syn::SyntheticConfig swept_config = sweptConfig(syn::LidarStamp::kEnd);
  syn::SyntheticConfig instant_config = swept_config;
  instant_config.timing = syn::SensorTimingConfig{};
  const syn::SyntheticRig swept(swept_config), instant(instant_config);
  int people = 0;
  for (const int i : framesWithPeople(swept, 600, 50)) {
    const syn::SyntheticFrame f = swept.render(i);
    std::map<int, std::pair<double, int>> time_sum;  // label -> (sum of times, count)
    for (std::size_t k = 0; k < f.cluster_labels.size(); ++k) {
      time_sum[f.cluster_labels[k]].first += f.cluster_time_s[k];
      ++time_sum[f.cluster_labels[k]].second;
    }
    for (const auto& kv : time_sum) {
      const double mean_time = kv.second.first / kv.second.second;
      const double stamp = swept.stampOf(i);
      const syn::SyntheticFrame then = instant.renderSnapshot(instant.worldAt(stamp + mean_time), i, stamp);
      const syn::SyntheticFrame at_stamp = instant.render(i);
      int n_swept = 0, n_then = 0, n_stamp = 0;
      const Eigen::Vector3d c_swept = centroidOf(f, kv.first, &n_swept);
      const Eigen::Vector3d c_then = centroidOf(then, kv.first, &n_then);
      const Eigen::Vector3d c_stamp = centroidOf(at_stamp, kv.first, &n_stamp);
      if (n_then < 10 || n_stamp < 10) continue;
      // Horizontally: which beams graze a limb's edge varies with millimetres of motion, and moves
      // a centroid of 20-30 points up or down by centimetres.
      EXPECT_LT((c_swept - c_then).head<2>().norm(), 0.03) << "frame " << i << " person " << kv.first;
      EXPECT_GT((c_swept - c_stamp).head<2>().norm(), 0.08) << "frame " << i << " person " << kv.first;
      // No part of the person is lost to the per-sector placement.
      EXPECT_NEAR(n_swept, n_then, 0.1 * n_then + 2) << "frame " << i << " person " << kv.first;
      ++people;
    }
  }
  EXPECT_GE(people, 3);
}

TEST(SyntheticTiming, WithoutTimingFlagsScansAreInstantaneousAndCarryNoTimes) {
  const syn::SyntheticRig rig(driveConfig(5, 100));
  EXPECT_EQ(rig.sweep(), nullptr);
  const syn::SyntheticFrame f = rig.render(50);
  EXPECT_TRUE(f.cluster_time_s.empty());
  EXPECT_TRUE(f.full_time_s.empty());
  // A sweep without the time field (a Velodyne that writes none) sweeps all the same.
  syn::SyntheticConfig no_field = sweptConfig(syn::LidarStamp::kEnd);
  no_field.timing.lidar_point_time = false;
  const syn::SyntheticRig swept(no_field);
  ASSERT_NE(swept.sweep(), nullptr);
  EXPECT_TRUE(swept.render(50).full_time_s.empty());
}

TEST(SyntheticTiming, BadTimingIsRefused) {
  syn::SyntheticConfig config = driveConfig(1, 10);
  config.timing.camera_time_offset_s = 0.6;
  EXPECT_THROW(syn::SyntheticRig{config}, std::invalid_argument);
  config.timing.camera_time_offset_s = 0.0;
  config.timing.lidar_point_time = true;  // times without a sweep
  EXPECT_THROW(syn::SyntheticRig{config}, std::invalid_argument);
  config.timing.lidar_stamp = syn::LidarStamp::kStart;
  config.timing.lidar_period_s = 0.0;
  EXPECT_THROW(syn::SyntheticRig{config}, std::invalid_argument);
  EXPECT_THROW(syn::lidarStampByName("middle"), std::invalid_argument);
  EXPECT_EQ(syn::lidarStampByName("end"), syn::LidarStamp::kEnd);
}

// An empty image region stays empty when the sensors see the world at different instants: a
// person who would show there in either sensor's view is out of that frame for both.
TEST(SyntheticTiming, TheEmptyRegionStaysEmptyWithALateCameraAndASweptScan) {
  syn::SyntheticConfig config = sweptConfig(syn::LidarStamp::kEnd);
  config.frames = 240;
  config.seed = 1;
  config.full_cloud = false;
  config.timing.camera_time_offset_s = 0.1;
  config.empty_image_region = syn::ImageRegion::kLeft;
  const syn::SyntheticRig rig(config);
  const syn::ColumnRange columns = rig.emptyColumns();
  int frames_with_people = 0;
  for (int i = 0; i < config.frames; i += 4) {
    const syn::SyntheticFrame frame = rig.render(i);
    EXPECT_EQ(cv::countNonZero(frame.mask.colRange(columns.begin, columns.end)), 0) << "frame " << i;
    const Eigen::Matrix3d R = rig.truthAt(i).rotationMatrix();
    for (const auto& p : frame.cluster_points) {
      const Eigen::Vector3d pc = R * p.cast<double>() + rig.truthAt(i).translation;
      if (pc.z() <= 0.0) continue;
      const Eigen::Vector2d px = config.rig.camera.project(pc);
      if (px.y() < -0.5 || px.y() >= config.rig.camera.height - 0.5) continue;
      EXPECT_FALSE(columns.contains(static_cast<int>(std::lround(px.x())))) << "frame " << i;
    }
    frames_with_people += frame.counts.mask_people > 0;
  }
  EXPECT_GT(frames_with_people, 5);
}
