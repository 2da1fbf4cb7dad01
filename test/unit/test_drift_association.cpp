// The drift watch pairs by association (issue 23): the frames the count rule did not keep are
// paired at the reference in use, as the calibration pairs them, so the watch sees about twice
// the pairs on these streams; without pairByAssociation, or within the skip rule, they are passed
// over; and association at the old reference does not hide a change: a 0.5 deg turn is confirmed
// no later than by the count rule's pairs alone, and the new extrinsic rests on as many of the
// count rule's pairs as without association.
#include "thermal_lidar_calibration/core/drift_monitor.hpp"

#include "../support/synthetic_pairs.hpp"
#include "thermal_lidar_calibration/synthetic/synthetic_rig.hpp"
#include "thermal_lidar_calibration/core/pose_difference.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <vector>

using namespace thermal_lidar_calibration;
using test_support::fieldsafeCamera;
using test_support::fieldsafeTruth;

namespace {

constexpr double kDeg = M_PI / 180.0;

std::vector<CalibrationPair> seenWith(const Extrinsic& truth, int count, std::uint64_t seed) {
  test_support::SyntheticPairsOptions o;
  o.pairs = count;
  o.seed = seed;
  return test_support::makeSyntheticPairs(fieldsafeCamera(), truth, o);
}

// Frame i of a drive at 10 frames a second: the count rule kept frame 10 i (`pairs`), and frame
// 10 i + `candidate_after` has its people and a post (`frames`, a candidate for association).
// Stamps in seconds from `start_s`, the stream in the order the frames came.
std::vector<CalibrationPair> drive(std::vector<CalibrationPair> pairs, std::vector<CalibrationPair> frames,
                                   std::uint64_t first_index, int candidate_after = 5) {
  std::vector<CalibrationPair> stream;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const std::uint64_t index = first_index + 10 * i;
    pairs[i].candidate_index = index;
    pairs[i].stamp_s = 0.1 * static_cast<double>(index);
    stream.push_back(std::move(pairs[i]));
    if (i >= frames.size()) continue;
    const double y = (i % 2 == 0 ? 1.0 : -1.0) * (1.0 + 0.1 * static_cast<double>(i % 7));
    CalibrationPair frame =
        test_support::asCandidateWithPost(std::move(frames[i]), index + static_cast<std::uint64_t>(candidate_after), y);
    frame.stamp_s = 0.1 * static_cast<double>(frame.candidate_index);
    stream.push_back(std::move(frame));
  }
  return stream;
}

struct Watched {
  std::uint64_t pairs = 0, association_pairs = 0, candidates = 0;
  DriftState state = DriftState::kOk;
  std::optional<double> first_error_stamp;
  std::optional<DriftCandidate> candidate;
};

Watched watch(const std::vector<CalibrationPair>& stream, bool associate) {
  CalibrationConfig calibration;
  calibration.num_threads = 1;
  DriftMonitor m(fieldsafeCamera(), fieldsafeTruth(), DriftConfig{}, calibration);
  if (associate) m.pairByAssociation(AssociationPairing{});
  for (const CalibrationPair& p : stream) m.add(p);
  return {m.pairsSeen(), m.associationPairs(), m.candidatesOffered(), m.state(), m.firstErrorStamp(), m.candidate()};
}

}  // namespace

TEST(DriftAssociation, CandidateFramesJoinTheWatchOnlyWhenItPairsByAssociation) {
  const auto stream = drive(seenWith(fieldsafeTruth(), 50, 21), seenWith(fieldsafeTruth(), 50, 22), 0);
  const Watched with = watch(stream, true);
  EXPECT_EQ(with.candidates, 50u);
  EXPECT_GE(with.association_pairs, 35u);  // most frames pair by the people who stand apart
  EXPECT_EQ(with.pairs, 50u + with.association_pairs);
  EXPECT_EQ(with.state, DriftState::kOk);  // the post and the association pairs move nothing

  const Watched counts = watch(stream, false);
  EXPECT_EQ(counts.candidates, 50u);
  EXPECT_EQ(counts.association_pairs, 0u);
  EXPECT_EQ(counts.pairs, 50u);
}

TEST(DriftAssociation, TheSkipRuleHoldsForTheWatchsAssociationPairs) {
  // Each candidate two frames after a kept pair: within skip_frames (3), so none pairs.
  const auto close = drive(seenWith(fieldsafeTruth(), 12, 31), seenWith(fieldsafeTruth(), 12, 32), 0, 2);
  EXPECT_EQ(watch(close, true).association_pairs, 0u);
  // Four frames after: all may pair.
  const auto apart = drive(seenWith(fieldsafeTruth(), 12, 31), seenWith(fieldsafeTruth(), 12, 32), 0, 4);
  EXPECT_GE(watch(apart, true).association_pairs, 9u);
}

TEST(DriftAssociation, AssociationAtTheOldReferenceDoesNotHideATurn) {
  const Extrinsic before = fieldsafeTruth();
  const Extrinsic after =
      synthetic::bumpedExtrinsic(before, Eigen::Vector3d(0.3, -0.8, 0.5), 0.5, Eigen::Vector3d::Zero());
  std::vector<CalibrationPair> stream = drive(seenWith(before, 40, 41), seenWith(before, 40, 42), 0);
  const double bump_s = 0.1 * 400.0;  // the first frame after the turn
  for (CalibrationPair& p : drive(seenWith(after, 70, 43), seenWith(after, 70, 44), 400)) stream.push_back(std::move(p));

  const Watched with = watch(stream, true);
  const Watched counts = watch(stream, false);
  ASSERT_TRUE(counts.first_error_stamp);
  ASSERT_TRUE(with.first_error_stamp);
  EXPECT_GE(*with.first_error_stamp, bump_s);
  // Confirmed in less driving than by the count rule's pairs alone: the turned frames still pair
  // by association at the old reference (0.5 deg is about 7 px here, people 20-50 px wide).
  EXPECT_LE(*with.first_error_stamp, *counts.first_error_stamp);
  EXPECT_GT(with.association_pairs, 60u);
  EXPECT_EQ(with.state, DriftState::kError);
  ASSERT_TRUE(with.candidate);
  // The new extrinsic rests on monitor_update_pairs of the count rule's pairs, as without
  // association, with the association pairs of that stretch besides.
  EXPECT_TRUE(with.candidate->complete);
  EXPECT_GT(with.candidate->pairs, static_cast<std::size_t>(DriftConfig{}.update_pairs));
  ASSERT_TRUE(counts.candidate);
  EXPECT_TRUE(counts.candidate->complete);
  EXPECT_EQ(counts.candidate->pairs, static_cast<std::size_t>(DriftConfig{}.update_pairs));
  EXPECT_LT(rotationErrorRad(with.candidate->extrinsic, after), 0.15 * kDeg);
  EXPECT_LT(translationErrorM(with.candidate->extrinsic, after), 0.02);
}
