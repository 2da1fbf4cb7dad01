// The ingest path measures each kept pair's people's motion from the scans around it (issue 21):
// a kept pair waits for its later scans, then carries velocities; the end of input finishes the
// waiting ones; frames that bring velocities, and builders without motion, keep pairs at once.

#include "thermal_lidar_calibration/core/dataset_builder.hpp"

#include "thermal_lidar_calibration/core/person_timing.hpp"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>

namespace tlc = thermal_lidar_calibration;
using tlc::GateDecision;

namespace {

constexpr int kWidth = 64;
constexpr int kHeight = 48;

tlc::CameraModel camera() {
  tlc::CameraModel c;
  c.width = kWidth;
  c.height = kHeight;
  c.fx = c.fy = 50.0;
  c.cx = kWidth / 2.0;
  c.cy = kHeight / 2.0;
  return c;
}

tlc::GateConfig gate(int skip_frames) {
  tlc::GateConfig g;
  g.skip_frames = skip_frames;
  return g;
}

// Scan k at 10 Hz: one person 8 m ahead coming closer at 2 m/s (label 20 + k: a detector's labels
// are per scan), its mask, the scan as the ingest path summarises it.
constexpr double kSpeed = 2.0;
double stampOf(int k) { return 100.0 + 0.1 * k; }

tlc::Frame frameAt(int k) {
  tlc::Frame f;
  f.stamp_s = stampOf(k);
  f.cloud_stamp_s = stampOf(k);
  f.camera_frame = "thermal_optical";
  f.lidar_frame = "velodyne";
  f.mask = cv::Mat::zeros(kHeight, kWidth, CV_8UC1);
  f.mask(cv::Rect(20, 5, 8, 30)).setTo(1);
  const float x = static_cast<float>(8.0 - kSpeed * 0.1 * k);
  for (int i = 0; i < 6; ++i) {
    f.points.emplace_back(x, 0.1f * static_cast<float>(i % 2), 0.3f * static_cast<float>(i));
    f.labels.push_back(20 + k);
  }
  return f;
}

tlc::ScanPeople scanAt(int k) {
  const tlc::Frame f = frameAt(k);
  return tlc::summariseScan(f.cloud_stamp_s, f.points, f.labels);
}

}  // namespace

TEST(DatasetBuilderMotion, AKeptPairWaitsForItsLaterScansThenCarriesTheVelocity) {
  tlc::DatasetBuilder builder(camera(), gate(3), tlc::MotionConfig{});
  ASSERT_TRUE(builder.tracksMotion());
  // Scans 0..2 before, the kept frame 3, then scans 4 and 5 (skipped by the skip rule).
  for (int k = 0; k <= 2; ++k) builder.observeScan(scanAt(k));
  builder.observeScan(scanAt(3));
  EXPECT_EQ(builder.offer([] { return frameAt(3); }).decision, GateDecision::kKept);
  EXPECT_EQ(builder.pendingPairs(), 1u);
  EXPECT_TRUE(builder.pairs().empty()) << "waits for the scans after it";
  builder.observeScan(scanAt(4));
  EXPECT_EQ(builder.pendingPairs(), 1u);
  builder.observeScan(scanAt(5));
  EXPECT_EQ(builder.pendingPairs(), 0u);
  ASSERT_EQ(builder.pairs().size(), 1u);
  const tlc::CalibrationPair& pair = builder.pairs().front();
  ASSERT_TRUE(tlc::hasMeasuredMotion(pair));
  ASSERT_EQ(pair.motion.size(), 1u);
  EXPECT_EQ(pair.motion[0].scans, 5);
  EXPECT_NEAR(pair.point_velocity[0].x(), -kSpeed, 1e-4);
  EXPECT_NEAR(pair.point_velocity[0].y(), 0.0, 1e-4);
  EXPECT_DOUBLE_EQ(pair.cloud_stamp_s, stampOf(3));
}

TEST(DatasetBuilderMotion, AFrameOfferedAfterItsLaterScansIsFinishedAtOnce) {
  // A synchronizer may hand over a frame only after later messages arrived.
  tlc::DatasetBuilder builder(camera(), gate(0), tlc::MotionConfig{});
  for (int k = 0; k <= 6; ++k) builder.observeScan(scanAt(k));
  EXPECT_EQ(builder.offer([] { return frameAt(4); }).decision, GateDecision::kKept);
  EXPECT_EQ(builder.pendingPairs(), 0u);
  ASSERT_EQ(builder.pairs().size(), 1u);
  EXPECT_NEAR(builder.pairs()[0].point_velocity[0].x(), -kSpeed, 1e-4);
}

TEST(DatasetBuilderMotion, TheEndOfInputFinishesWaitingPairsWithTheScansThereAre) {
  tlc::DatasetBuilder builder(camera(), gate(0), tlc::MotionConfig{});
  builder.observeScan(scanAt(0));
  builder.observeScan(scanAt(1));
  EXPECT_EQ(builder.offer([] { return frameAt(1); }).decision, GateDecision::kKept);
  EXPECT_EQ(builder.pendingPairs(), 1u);
  builder.flushPending();
  ASSERT_EQ(builder.pairs().size(), 1u);
  EXPECT_EQ(builder.pairs()[0].motion[0].scans, 2);  // only the scan before it
  EXPECT_NEAR(builder.pairs()[0].point_velocity[0].x(), -kSpeed, 1e-4);
  // A pair alone in its scans has its people not measured: no velocity.
  tlc::DatasetBuilder alone(camera(), gate(0), tlc::MotionConfig{});
  alone.offer([] { return frameAt(7); });
  alone.flushPending();
  ASSERT_EQ(alone.pairs().size(), 1u);
  EXPECT_FALSE(alone.pairs()[0].motion[0].measured());
  EXPECT_EQ(alone.pairs()[0].point_velocity[0], Eigen::Vector3f::Zero());
}

TEST(DatasetBuilderMotion, FramesWithVelocitiesAndBuildersWithoutMotionKeepAtOnce) {
  tlc::DatasetBuilder builder(camera(), gate(0), tlc::MotionConfig{});
  tlc::Frame stored = frameAt(2);
  stored.point_velocity.assign(stored.points.size(), Eigen::Vector3f(-1.5f, 0.0f, 0.0f));
  EXPECT_EQ(builder.restore(stored).decision, GateDecision::kKept);
  EXPECT_EQ(builder.pendingPairs(), 0u);
  ASSERT_EQ(builder.pairs().size(), 1u);
  EXPECT_FLOAT_EQ(builder.pairs()[0].point_velocity[0].x(), -1.5f);

  tlc::DatasetBuilder plain(camera(), gate(0));
  EXPECT_FALSE(plain.tracksMotion());
  plain.observeScan(scanAt(0));  // ignored
  EXPECT_EQ(plain.offer([] { return frameAt(0); }).decision, GateDecision::kKept);
  ASSERT_EQ(plain.pairs().size(), 1u);
  EXPECT_TRUE(plain.pairs()[0].point_velocity.empty());
}

TEST(DatasetBuilderMotion, ResetForgetsWaitingPairsAndScansAndOldScansAreDropped) {
  tlc::DatasetBuilder builder(camera(), gate(0), tlc::MotionConfig{});
  for (int k = 0; k <= 3; ++k) builder.observeScan(scanAt(k));
  builder.offer([] { return frameAt(3); });
  builder.reset();
  EXPECT_EQ(builder.pendingPairs(), 0u);
  builder.flushPending();
  EXPECT_TRUE(builder.pairs().empty());
  // An hour of scans with nothing kept holds only the last few.
  for (int k = 0; k < 36000; k += 1) builder.observeScan(scanAt(k));
  EXPECT_LE(builder.latestMotion().size(), 1u);
  EXPECT_NEAR(builder.latestMotion().at(0).velocity_mps.x(), -kSpeed, 1e-3);
  EXPECT_DOUBLE_EQ(builder.latestScanStamp(), stampOf(35999));
}
