// The shared ingest path: skip rule before decoding, decode errors counted (never fatal),
// validation against the camera, people counts, gate, and the pairs it builds.

#include "thermal_lidar_calibration/core/dataset_builder.hpp"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include <stdexcept>
#include <string>

namespace tlc = thermal_lidar_calibration;
using tlc::GateDecision;

namespace {

constexpr int kWidth = 64;
constexpr int kHeight = 48;

tlc::CameraModel camera(int width = kWidth, int height = kHeight) {
  tlc::CameraModel c;
  c.width = width;
  c.height = height;
  c.fx = 50.0;
  c.fy = 50.0;
  c.cx = width / 2.0;
  c.cy = height / 2.0;
  return c;
}

tlc::GateConfig gate(int skip_frames = 3, int min_points = 3) {
  tlc::GateConfig g;
  g.max_people = 3;
  g.skip_frames = skip_frames;
  g.min_points_per_cluster = min_points;
  return g;
}

// A frame with `people` persons in the mask (ids 1..people) and `points_each` points per
// person cluster (labels 10, 11, ...).
tlc::Frame frame(int mask_people, int cluster_people, int points_each = 5, double stamp = 1.0) {
  tlc::Frame f;
  f.stamp_s = stamp;
  f.camera_frame = "thermal_optical";
  f.lidar_frame = "velodyne";
  f.image = cv::Mat(kHeight, kWidth, CV_16UC1, cv::Scalar(3000));
  f.mask = cv::Mat::zeros(kHeight, kWidth, CV_8UC1);
  for (int i = 0; i < mask_people; ++i) {
    f.mask(cv::Rect(2 + 12 * i, 5, 8, 30)).setTo(i + 1);
  }
  for (int i = 0; i < cluster_people; ++i) {
    for (int k = 0; k < points_each; ++k) {
      f.points.emplace_back(5.0f, 0.5f * static_cast<float>(i), 0.1f * static_cast<float>(k));
      f.labels.push_back(10 + i);
    }
  }
  return f;
}

}  // namespace

TEST(DatasetBuilder, InvalidCameraOrGateThrows) {
  EXPECT_THROW(tlc::DatasetBuilder(tlc::CameraModel{}, gate()), std::invalid_argument);
  tlc::GateConfig bad = gate();
  bad.max_people = 0;
  EXPECT_THROW(tlc::DatasetBuilder(camera(), bad), std::invalid_argument);
}

TEST(DatasetBuilder, KeptFrameBuildsThePair) {
  tlc::DatasetBuilder builder(camera(), gate());
  tlc::Frame f = frame(2, 2, 6, 12.5);
  f.mask(cv::Rect(2, 5, 8, 30)).setTo(200);  // ids 200 and 2
  f.nonfinite_points_dropped = 4;
  const tlc::OfferOutcome out = builder.offer([&] { return f; });
  EXPECT_EQ(out.decision, GateDecision::kKept);
  EXPECT_TRUE(out.error.empty());
  EXPECT_EQ(out.mask_people, 2);
  EXPECT_EQ(out.cluster_people, 2);

  ASSERT_EQ(builder.pairs().size(), 1u);
  const tlc::CalibrationPair& p = builder.pairs()[0];
  EXPECT_DOUBLE_EQ(p.stamp_s, 12.5);
  EXPECT_EQ(p.people, 2);
  ASSERT_EQ(p.mask.type(), CV_8UC1);
  EXPECT_EQ(p.mask.size(), cv::Size(kWidth, kHeight));
  double min_value = 0, max_value = 0;
  cv::minMaxLoc(p.mask, &min_value, &max_value);
  EXPECT_EQ(min_value, 0.0);
  EXPECT_EQ(max_value, 1.0);
  EXPECT_EQ(cv::countNonZero(p.mask), 2 * 8 * 30);
  EXPECT_EQ(p.image.type(), CV_16UC1);
  EXPECT_EQ(p.image.size(), cv::Size(kWidth, kHeight));
  ASSERT_EQ(p.points.size(), 12u);
  EXPECT_EQ(p.labels, f.labels);
  EXPECT_EQ(p.points[7], f.points[7]);
  EXPECT_EQ(builder.cameraFrame(), "thermal_optical");
  EXPECT_EQ(builder.lidarFrame(), "velodyne");
  EXPECT_EQ(builder.counts()[GateDecision::kKept], 1u);
  EXPECT_EQ(builder.counts().nonfinite_points_dropped, 4u);
  EXPECT_TRUE(p.point_time_s.empty());
}

// Issue 21: the clusters' per-point times and stamp reach the pair as decoded.
TEST(DatasetBuilder, PointTimesAndTheCloudStampReachThePair) {
  tlc::DatasetBuilder builder(camera(), gate());
  tlc::Frame f = frame(1, 1, 4, 12.5);
  f.cloud_stamp_s = 12.47;
  f.point_time_s = {-0.09f, -0.06f, -0.05f, -0.01f};
  ASSERT_EQ(builder.offer([&] { return f; }).decision, GateDecision::kKept);
  const tlc::CalibrationPair& p = builder.pairs().back();
  EXPECT_EQ(p.point_time_s, f.point_time_s);
  EXPECT_DOUBLE_EQ(p.cloud_stamp_s, 12.47);
}

TEST(DatasetBuilder, ImageWrappingExternalBufferIsCopied) {
  tlc::DatasetBuilder builder(camera(), gate());
  std::vector<std::uint16_t> buffer(kWidth * kHeight, 1234);
  {
    tlc::Frame f = frame(1, 1);
    f.image = cv::Mat(kHeight, kWidth, CV_16UC1, buffer.data());
    EXPECT_EQ(builder.offer([&] { return f; }).decision, GateDecision::kKept);
  }
  std::fill(buffer.begin(), buffer.end(), 0);
  EXPECT_EQ(builder.pairs().at(0).image.at<std::uint16_t>(3, 4), 1234);
}

TEST(DatasetBuilder, SkipHappensBeforeDecode) {
  tlc::DatasetBuilder builder(camera(), gate(3));
  int decode_calls = 0;
  auto decode = [&] {
    ++decode_calls;
    return frame(1, 1);
  };
  EXPECT_EQ(builder.offer(decode).decision, GateDecision::kKept);
  EXPECT_EQ(decode_calls, 1);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(builder.offer(decode).decision, GateDecision::kSkipped) << "candidate " << i;
  }
  EXPECT_EQ(decode_calls, 1) << "decode must not run for skipped frames";
  EXPECT_EQ(builder.offer(decode).decision, GateDecision::kKept);
  EXPECT_EQ(decode_calls, 2);
  EXPECT_EQ(builder.pairs().size(), 2u);
  EXPECT_EQ(builder.counts()[GateDecision::kSkipped], 3u);

  // A skipped frame is skipped even if it could not have been decoded.
  int throwing_calls = 0;
  auto throwing = [&]() -> tlc::Frame {
    ++throwing_calls;
    throw std::invalid_argument("unsupported encoding rgb8");
  };
  EXPECT_EQ(builder.offer(throwing).decision, GateDecision::kSkipped);
  EXPECT_EQ(throwing_calls, 0);
}

TEST(DatasetBuilder, BadDecodeIsCountedAndDoesNotStopTheBuilder) {
  tlc::DatasetBuilder builder(camera(), gate());
  const tlc::OfferOutcome bad = builder.offer([]() -> tlc::Frame {
    throw std::invalid_argument("clusters have no 'label' field");
  });
  EXPECT_EQ(bad.decision, GateDecision::kBadMessage);
  EXPECT_EQ(bad.error, "clusters have no 'label' field");

  const tlc::OfferOutcome other = builder.offer([]() -> tlc::Frame {
    throw std::runtime_error("cv_bridge failed");
  });
  EXPECT_EQ(other.decision, GateDecision::kBadMessage);
  EXPECT_NE(other.error.find("cv_bridge failed"), std::string::npos) << other.error;

  // A bad frame does not arm the skip: the next good one is kept.
  EXPECT_EQ(builder.offer([] { return frame(1, 1); }).decision, GateDecision::kKept);
  EXPECT_EQ(builder.counts()[GateDecision::kBadMessage], 2u);
  EXPECT_EQ(builder.counts()[GateDecision::kKept], 1u);
  EXPECT_EQ(builder.pairs().size(), 1u);
}

TEST(DatasetBuilder, MaskSizeMismatchIsBadMessage) {
  tlc::DatasetBuilder builder(camera(640, 512), gate());
  const tlc::OfferOutcome out = builder.offer([] {
    tlc::Frame f = frame(1, 1);
    f.mask = cv::Mat::zeros(480, 640, CV_8UC1);
    f.mask(cv::Rect(10, 10, 20, 40)).setTo(1);
    f.image = cv::Mat();
    return f;
  });
  EXPECT_EQ(out.decision, GateDecision::kBadMessage);
  EXPECT_EQ(out.error.rfind("mask is 640x480 but camera_info says 640x512: ", 0), 0u) << out.error;
  EXPECT_TRUE(builder.pairs().empty());
  EXPECT_EQ(builder.counts()[GateDecision::kBadMessage], 1u);
}

TEST(DatasetBuilder, OtherMalformedFramesAreBadMessages) {
  tlc::DatasetBuilder builder(camera(), gate(0));
  auto expect_bad = [&](tlc::Frame f, const std::string& fragment) {
    const tlc::OfferOutcome out = builder.offer([&] { return f; });
    EXPECT_EQ(out.decision, GateDecision::kBadMessage) << fragment;
    EXPECT_NE(out.error.find(fragment), std::string::npos) << out.error;
  };
  tlc::Frame image_size = frame(1, 1);
  image_size.image = cv::Mat::zeros(kHeight + 1, kWidth, CV_8UC1);
  expect_bad(image_size, "image is 64x49 but mask is 64x48");

  tlc::Frame labels = frame(1, 1);
  labels.labels.pop_back();
  expect_bad(labels, "5 points but 4 labels");

  tlc::Frame times = frame(1, 1);
  times.point_time_s = {0.0f, 0.01f};
  expect_bad(times, "5 points but 2 point times");

  tlc::Frame mask_type = frame(1, 1);
  mask_type.mask = cv::Mat::zeros(kHeight, kWidth, CV_32FC1);
  expect_bad(mask_type, "mask");

  // A frame without an image is fine.
  tlc::Frame no_image = frame(1, 1);
  no_image.image = cv::Mat();
  EXPECT_EQ(builder.offer([&] { return no_image; }).decision, GateDecision::kKept);
  EXPECT_TRUE(builder.pairs().back().image.empty());

  // Once pairs exist, frames from other sensors are refused.
  tlc::Frame other_frames = frame(1, 1);
  other_frames.lidar_frame = "os_sensor";
  expect_bad(other_frames, "os_sensor");
  EXPECT_EQ(builder.counts()[GateDecision::kBadMessage], 5u);
  EXPECT_EQ(builder.pairs().size(), 1u);
}

TEST(DatasetBuilder, GateDecisionsFromCounts) {
  tlc::DatasetBuilder builder(camera(), gate(0, 3));
  const tlc::OfferOutcome mismatch = builder.offer([] { return frame(2, 1); });
  EXPECT_EQ(mismatch.decision, GateDecision::kCountMismatch);
  EXPECT_EQ(mismatch.mask_people, 2);
  EXPECT_EQ(mismatch.cluster_people, 1);
  EXPECT_EQ(builder.offer([] { return frame(0, 0); }).decision, GateDecision::kNoPeople);
  EXPECT_EQ(builder.offer([] { return frame(4, 4); }).decision, GateDecision::kTooManyPeople);
  EXPECT_TRUE(builder.pairs().empty());
  EXPECT_EQ(builder.counts().considered(), 3u);
}

TEST(DatasetBuilder, SmallClusterRejectsTheFrame) {
  tlc::DatasetBuilder builder(camera(), gate(0, 3));
  tlc::Frame f = frame(2, 2, 5);
  // Second person's cluster has only two points.
  f.points.resize(7);
  f.labels.resize(7);
  EXPECT_EQ(builder.offer([&] { return f; }).decision, GateDecision::kSmallCluster);
  EXPECT_EQ(builder.offer([] { return frame(2, 2, 3); }).decision, GateDecision::kKept);
  EXPECT_EQ(builder.counts()[GateDecision::kSmallCluster], 1u);
  EXPECT_EQ(builder.pairs().size(), 1u);
}

TEST(DatasetBuilder, RestoredFramesAreCheckedLikeLiveOnesButNotGatedAgain) {
  tlc::DatasetBuilder builder(camera(), gate());
  // Unequal counts would be rejected live; a frame kept in an earlier session stays kept.
  EXPECT_EQ(builder.restore(frame(2, 1)).decision, GateDecision::kKept);
  ASSERT_EQ(builder.pairs().size(), 1u);
  EXPECT_EQ(builder.pairs()[0].mask.at<std::uint8_t>(6, 3), 1);  // stored as 0/1
  EXPECT_EQ(builder.pairs()[0].people, 2);                       // counted like a live frame
  EXPECT_EQ(builder.counts().considered(), 0u);                  // no gating
  EXPECT_EQ(builder.cameraFrame(), "thermal_optical");

  // Recorded with another camera: the live check refuses it and says why.
  tlc::Frame wrong = frame(1, 1);
  wrong.mask = cv::Mat::zeros(kHeight + 2, kWidth, CV_8UC1);
  const tlc::OfferOutcome bad_size = builder.restore(wrong);
  EXPECT_EQ(bad_size.decision, GateDecision::kBadMessage);
  EXPECT_NE(bad_size.error.find("camera_info says"), std::string::npos) << bad_size.error;
  // Points without labels: the live check, not a silent pair.
  tlc::Frame unlabeled = frame(1, 1);
  unlabeled.labels.pop_back();
  EXPECT_EQ(builder.restore(unlabeled).decision, GateDecision::kBadMessage);
  EXPECT_EQ(builder.pairs().size(), 1u);

  EXPECT_EQ(builder.offer([] { return frame(1, 1); }).decision, GateDecision::kKept);
  builder.reset();
  EXPECT_TRUE(builder.pairs().empty());
  EXPECT_EQ(builder.counts().considered(), 0u);
  EXPECT_TRUE(builder.cameraFrame().empty());
  // No pending skip after reset.
  EXPECT_EQ(builder.offer([] { return frame(1, 1); }).decision, GateDecision::kKept);
}

namespace {

tlc::Frame frameWithIds(const std::string& camera_frame, const std::string& lidar_frame,
                        double stamp) {
  tlc::Frame f = frame(1, 1, 5, stamp);
  f.camera_frame = camera_frame;
  f.lidar_frame = lidar_frame;
  return f;
}

tlc::OfferOutcome offer(tlc::DatasetBuilder& builder, const tlc::Frame& f) {
  return builder.offer([&] { return f; });
}

}  // namespace

// One stray frame with other ids came first, and 1,197 of 1,201 frames of the real drive were
// refused as "frame ids changed" (issue 12, item 7). A single frame no longer decides the ids.
TEST(DatasetBuilder, OneStrayFrameFirstDoesNotBlockTheDrive) {
  tlc::DatasetBuilder builder(camera(), gate(0));
  EXPECT_EQ(offer(builder, frameWithIds("other_camera", "other_lidar", 1.0)).decision,
            GateDecision::kKept);
  EXPECT_FALSE(builder.frameIdsLocked());
  // The drive's first frame is refused (one against one), its second outnumbers the stray one.
  EXPECT_EQ(offer(builder, frameWithIds("thermal_optical", "velodyne", 2.0)).decision,
            GateDecision::kBadMessage);
  EXPECT_EQ(offer(builder, frameWithIds("thermal_optical", "velodyne", 3.0)).decision,
            GateDecision::kKept);
  EXPECT_EQ(builder.cameraFrame(), "thermal_optical");
  EXPECT_EQ(builder.lidarFrame(), "velodyne");
  EXPECT_EQ(builder.pairsDroppedForFrameIds(), 1u);
  ASSERT_EQ(builder.pairs().size(), 1u);
  EXPECT_DOUBLE_EQ(builder.pairs()[0].stamp_s, 3.0);
  for (int i = 0; i < 20; ++i) {
    EXPECT_EQ(offer(builder, frameWithIds("thermal_optical", "velodyne", 4.0 + i)).decision,
              GateDecision::kKept);
  }
  EXPECT_EQ(builder.pairs().size(), 21u);
  EXPECT_TRUE(builder.frameIdsLocked());
  EXPECT_FALSE(builder.frameIdConflict());
}

// Once kLockPairs pairs agree, the ids hold: a stray frame is refused, and frames that keep
// disagreeing are reported with both ids; a frame with the dataset's ids ends the report.
TEST(DatasetBuilder, LockedIdsRefuseOthersAndReportAConflictThatPersists) {
  tlc::DatasetBuilder builder(camera(), gate(0));
  for (int i = 0; i < 3; ++i) offer(builder, frameWithIds("thermal_optical", "velodyne", 1.0 + i));
  ASSERT_TRUE(builder.frameIdsLocked());
  for (int i = 0; i < 9; ++i) {
    const tlc::OfferOutcome out = offer(builder, frameWithIds("cam2", "lidar2", 10.0 + i));
    EXPECT_EQ(out.decision, GateDecision::kBadMessage);
    EXPECT_NE(out.error.find("frame ids changed: camera 'cam2', lidar 'lidar2'"), std::string::npos)
        << out.error;
    EXPECT_FALSE(builder.frameIdConflict(10));
  }
  offer(builder, frameWithIds("cam2", "lidar2", 19.0));
  const auto conflict = builder.frameIdConflict(10);
  ASSERT_TRUE(conflict);
  EXPECT_EQ(conflict->camera_frame, "thermal_optical");
  EXPECT_EQ(conflict->lidar_frame, "velodyne");
  EXPECT_EQ(conflict->other_camera_frame, "cam2");
  EXPECT_EQ(conflict->other_lidar_frame, "lidar2");
  EXPECT_EQ(conflict->frames_in_a_row, 10u);
  EXPECT_EQ(builder.pairs().size(), 3u);  // never dropped once locked
  offer(builder, frameWithIds("thermal_optical", "velodyne", 30.0));
  EXPECT_FALSE(builder.frameIdConflict(10));
  builder.reset();
  EXPECT_FALSE(builder.frameIdsLocked());
  EXPECT_EQ(offer(builder, frameWithIds("cam2", "lidar2", 40.0)).decision, GateDecision::kKept);
}

// Issue 23: with association on, the frames the count rule rejects but that show people in both
// modalities are kept aside as candidates; skipped and empty frames are not, and nothing changes
// for the count rule's pairs or counts.
TEST(DatasetBuilder, KeepsAssociationCandidatesOnlyWhenAskedAndNeverSkippedOnes) {
  for (const bool keep : {false, true}) {
    tlc::DatasetBuilder builder(camera(), gate(1));
    builder.keepAssociationCandidates(keep);
    EXPECT_EQ(builder.offer([] { return frame(2, 3, 5, 1.0); }).decision, GateDecision::kCountMismatch);
    EXPECT_EQ(builder.offer([] { return frame(1, 1, 5, 1.1); }).decision, GateDecision::kKept);
    EXPECT_EQ(builder.offer([] { return frame(1, 2, 5, 1.2); }).decision, GateDecision::kSkipped);
    EXPECT_EQ(builder.offer([] { return frame(0, 2, 5, 1.3); }).decision, GateDecision::kCountMismatch);
    EXPECT_EQ(builder.offer([] { return frame(1, 2, 5, 1.4); }).decision, GateDecision::kCountMismatch);
    ASSERT_EQ(builder.pairs().size(), 1u);
    EXPECT_EQ(builder.pairs()[0].candidate_index, 1u);
    EXPECT_EQ(builder.pairs()[0].rule, tlc::PairRule::kCounts);
    EXPECT_EQ(builder.counts()[GateDecision::kCountMismatch], 3u);
    if (!keep) {
      EXPECT_TRUE(builder.candidates().empty());
      continue;
    }
    const std::vector<tlc::CalibrationPair> candidates = builder.takeCandidates();
    ASSERT_EQ(candidates.size(), 2u);  // not the skipped one, not the one without a mask person
    EXPECT_EQ(candidates[0].candidate_index, 0u);
    EXPECT_EQ(candidates[1].candidate_index, 4u);
    EXPECT_EQ(candidates[0].rule, tlc::PairRule::kAssociation);
    EXPECT_TRUE(candidates[0].mask.empty());
    ASSERT_EQ(candidates[0].regions.type(), CV_16UC1);
    EXPECT_EQ(candidates[0].regions.at<std::uint16_t>(10, 15), 2);  // the mask's id 2
    EXPECT_EQ(candidates[0].points.size(), 15u);
    EXPECT_TRUE(builder.candidates().empty());
  }
}

// Issue 23, the live node: candidates are bounded. Past the bound every second one held goes and
// from then on only every second (fourth, ...) new one is kept: those held stay evenly spread over
// the whole drive (not only its start or its end), and every one passed over is counted.
TEST(DatasetBuilder, BoundedCandidatesStayEvenlySpreadOverTheDriveAndDropsAreCounted) {
  tlc::DatasetBuilder builder(camera(), gate(0));
  builder.keepAssociationCandidates(true, 4);
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(builder.offer([i] { return frame(1, 2, 5, 1.0 + i); }).decision, GateDecision::kCountMismatch);
  }
  ASSERT_EQ(builder.candidates().size(), 4u);
  EXPECT_EQ(builder.candidatesDropped(), 0u);
  for (int i = 4; i < 16; ++i) builder.offer([i] { return frame(1, 2, 5, 1.0 + i); });
  // 16 seen with a bound of 4: every fourth, from the first on.
  ASSERT_EQ(builder.candidates().size(), 4u);
  for (std::size_t k = 0; k < 4; ++k) EXPECT_EQ(builder.candidates()[k].candidate_index, 4 * k) << k;
  EXPECT_EQ(builder.candidatesDropped(), 12u);
  EXPECT_TRUE(builder.pairs().empty());  // the count rule's pairs are not touched
  builder.reset();
  EXPECT_TRUE(builder.candidates().empty());
  EXPECT_EQ(builder.candidatesDropped(), 0u);
  EXPECT_THROW(builder.keepAssociationCandidates(true, 0), std::invalid_argument);
}

// Issue 24: with candidates and skipped frames kept, the frames the skip rule passes over are
// decoded and held apart from the candidates (outside_skip_rule, no image); the gate's decisions
// and counts are what they were. A skipped frame without people in both modalities, that cannot
// be decoded or with other ids is left out without a word: it was never going to be kept.
TEST(DatasetBuilder, SkippedFramesAreHeldApartWhenAskedAndTheGateCountsNothingNew) {
  for (const bool keep : {false, true}) {
    tlc::DatasetBuilder builder(camera(), gate(4));
    builder.keepAssociationCandidates(true);
    builder.keepSkippedFrames(keep);
    EXPECT_EQ(builder.keepsSkippedFrames(), keep);
    EXPECT_EQ(offer(builder, frame(1, 1, 5, 1.0)).decision, GateDecision::kKept);
    const tlc::OfferOutcome held = offer(builder, frame(1, 2, 5, 1.1));
    EXPECT_EQ(held.decision, GateDecision::kSkipped);
    EXPECT_EQ(held.skipped_held, keep);
    const tlc::OfferOutcome corrupt = builder.offer([]() -> tlc::Frame { throw std::invalid_argument("corrupt"); });
    EXPECT_EQ(corrupt.decision, GateDecision::kSkipped);
    EXPECT_FALSE(corrupt.skipped_held);
    EXPECT_TRUE(corrupt.error.empty());
    EXPECT_FALSE(offer(builder, frame(0, 2, 5, 1.3)).skipped_held);
    EXPECT_EQ(offer(builder, frameWithIds("cam2", "lidar2", 1.4)).decision, GateDecision::kSkipped);
    EXPECT_EQ(offer(builder, frame(1, 1, 5, 1.5)).decision, GateDecision::kKept);
    EXPECT_EQ(builder.counts()[GateDecision::kSkipped], 4u);
    EXPECT_EQ(builder.counts()[GateDecision::kBadMessage], 0u);
    EXPECT_EQ(builder.pairs().size(), 2u);
    EXPECT_TRUE(builder.candidates().empty());
    EXPECT_FALSE(builder.frameIdConflict(1));
    if (!keep) {
      EXPECT_TRUE(builder.skippedFrames().empty());
      continue;
    }
    const std::vector<tlc::CalibrationPair> skipped = builder.takeSkippedFrames();
    ASSERT_EQ(skipped.size(), 1u);
    EXPECT_EQ(skipped[0].candidate_index, 1u);
    EXPECT_TRUE(skipped[0].outside_skip_rule);
    EXPECT_EQ(skipped[0].rule, tlc::PairRule::kAssociation);
    EXPECT_TRUE(skipped[0].image.empty());
    EXPECT_TRUE(skipped[0].mask.empty());
    EXPECT_EQ(skipped[0].regions.type(), CV_16UC1);
    EXPECT_EQ(skipped[0].points.size(), 10u);
    EXPECT_TRUE(builder.skippedFrames().empty());
  }
  // Without candidates there is no association to pair them.
  tlc::DatasetBuilder counts_only(camera(), gate(4));
  counts_only.keepSkippedFrames(true);
  EXPECT_FALSE(counts_only.keepsSkippedFrames());
  offer(counts_only, frame(1, 1, 5, 1.0));
  offer(counts_only, frame(1, 2, 5, 1.1));
  EXPECT_TRUE(counts_only.skippedFrames().empty());
}

// ~resume and calibrate_bag on a dataset bag: a stored association candidate is held as one again,
// at its place in the session that stored it (the skip rule between association pairs counts in
// it), and live frames are numbered after the stored ones.
TEST(DatasetBuilder, RestoredCandidatesKeepTheirPlaceAndLiveFramesFollowThem) {
  tlc::DatasetBuilder builder(camera(), gate(3));
  builder.keepAssociationCandidates(true);
  const tlc::OfferOutcome pair = builder.restore(frame(1, 1, 5, 1.0), {false, 7});
  EXPECT_EQ(pair.decision, GateDecision::kKept);
  EXPECT_FALSE(pair.candidate);
  const tlc::OfferOutcome held = builder.restore(frame(1, 2, 5, 1.5), {true, 12});
  EXPECT_EQ(held.decision, GateDecision::kCountMismatch);  // what the count rule says of it
  EXPECT_TRUE(held.candidate);
  EXPECT_EQ(held.frame_index, 12u);
  ASSERT_EQ(builder.pairs().size(), 1u);
  EXPECT_EQ(builder.pairs()[0].candidate_index, 7u);
  ASSERT_EQ(builder.candidates().size(), 1u);
  EXPECT_EQ(builder.candidates()[0].candidate_index, 12u);
  EXPECT_EQ(builder.candidates()[0].rule, tlc::PairRule::kAssociation);
  EXPECT_TRUE(builder.candidates()[0].mask.empty());
  EXPECT_EQ(builder.candidates()[0].regions.type(), CV_16UC1);
  EXPECT_EQ(builder.counts().considered(), 0u);  // stored frames are not gated again
  // The next live frame comes after them (and is not skipped: the skip was armed in that session).
  const tlc::OfferOutcome live = builder.offer([] { return frame(1, 2, 5, 2.0); });
  EXPECT_EQ(live.decision, GateDecision::kCountMismatch);
  EXPECT_TRUE(live.candidate);
  EXPECT_EQ(live.frame_index, 13u);
  ASSERT_EQ(builder.candidates().size(), 2u);
  EXPECT_EQ(builder.candidates()[1].candidate_index, 13u);
}

// Issue 24, ~resume: a stored skipped frame is held as one again at its place when the builder
// keeps skipped frames, and left out (still kSkipped) when it does not.
TEST(DatasetBuilder, RestoredSkippedFramesAreHeldOnlyWhenTheBuilderKeepsThem) {
  for (const bool keep : {false, true}) {
    tlc::DatasetBuilder builder(camera(), gate(3));
    builder.keepAssociationCandidates(true);
    builder.keepSkippedFrames(keep);
    EXPECT_EQ(builder.restore(frame(1, 1, 5, 1.0), {false, 7}).decision, GateDecision::kKept);
    const tlc::OfferOutcome skipped = builder.restore(frame(1, 2, 5, 1.1), {true, 8, true});
    EXPECT_EQ(skipped.decision, GateDecision::kSkipped);
    EXPECT_EQ(skipped.skipped_held, keep);
    EXPECT_FALSE(skipped.candidate);
    EXPECT_TRUE(builder.candidates().empty());
    ASSERT_EQ(builder.skippedFrames().size(), keep ? 1u : 0u);
    if (keep) {
      EXPECT_EQ(builder.skippedFrames()[0].candidate_index, 8u);
      EXPECT_TRUE(builder.skippedFrames()[0].outside_skip_rule);
    }
  }
}

TEST(DatasetBuilder, StoredCandidatesAreLeftOutWithoutAssociationAndBecomePairsUnderTodaysCountRule) {
  tlc::DatasetBuilder counts_only(camera(), gate(3));
  const tlc::OfferOutcome left_out = counts_only.restore(frame(1, 2, 5, 1.0), {true, 4});
  EXPECT_EQ(left_out.decision, GateDecision::kCountMismatch);
  EXPECT_FALSE(left_out.candidate);
  EXPECT_TRUE(counts_only.pairs().empty());
  EXPECT_TRUE(counts_only.candidates().empty());

  // Stored as a candidate for more people than H_max then; H_max is 3 here, so today it is a pair.
  tlc::DatasetBuilder builder(camera(), gate(3));
  builder.keepAssociationCandidates(true);
  const tlc::OfferOutcome promoted = builder.restore(frame(2, 2, 5, 1.0), {true, 4});
  EXPECT_EQ(promoted.decision, GateDecision::kKept);
  EXPECT_FALSE(promoted.candidate);
  ASSERT_EQ(builder.pairs().size(), 1u);
  EXPECT_EQ(builder.pairs()[0].rule, tlc::PairRule::kCounts);
  EXPECT_EQ(builder.pairs()[0].candidate_index, 4u);
  EXPECT_TRUE(builder.candidates().empty());
  // A dataset bag from before frame numbers were recorded: stored frames numbered in order.
  EXPECT_EQ(builder.restore(frame(1, 1, 5, 2.0)).frame_index, 5u);
  EXPECT_EQ(builder.restore(frame(1, 1, 5, 3.0)).frame_index, 6u);
}
