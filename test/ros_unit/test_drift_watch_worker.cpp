// DriftWatchWorker: the node's drift watch on its own thread gives what DriftMonitor gives on the
// same pairs in the same order (the verdicts do not depend on when the pairs arrive), confirms a
// bump, and an accepted update becomes the reference.
#include "thermal_lidar_calibration/node/drift_watch_worker.hpp"

#include "../support/synthetic_pairs.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <thread>
#include <vector>

using namespace thermal_lidar_calibration;
using test_support::fieldsafeCamera;
using test_support::fieldsafeTruth;

namespace {

// 40 pairs seen with the truth, then 40 after a 0.5 deg turn about (0.3, -0.8, 0.5), stamped
// 100, 101, ...
struct BumpStream {
  Extrinsic after;
  std::vector<CalibrationPair> pairs;
};
const BumpStream& bumpStream() {
  static const BumpStream stream = [] {
    BumpStream s;
    const Eigen::Matrix3d turn =
        Eigen::AngleAxisd(0.5 * M_PI / 180.0, Eigen::Vector3d(0.3, -0.8, 0.5).normalized())
            .toRotationMatrix();
    s.after = Extrinsic::fromRotationMatrix(turn * fieldsafeTruth().rotationMatrix(),
                                            fieldsafeTruth().translation);
    test_support::SyntheticPairsOptions o;
    o.pairs = 40;
    o.seed = 41;
    s.pairs = test_support::makeSyntheticPairs(fieldsafeCamera(), fieldsafeTruth(), o);
    o.seed = 42;
    for (CalibrationPair& p : test_support::makeSyntheticPairs(fieldsafeCamera(), s.after, o)) {
      s.pairs.push_back(std::move(p));
    }
    for (std::size_t i = 0; i < s.pairs.size(); ++i) s.pairs[i].stamp_s = 100.0 + i;
    return s;
  }();
  return stream;
}

DriftConfig fastDrift() {
  DriftConfig drift;
  drift.update_pairs = 30;  // final within the 40 pairs after the bump
  return drift;
}

}  // namespace

TEST(DriftWatchWorker, GivesWhatTheMonitorGivesOnTheSamePairsAndConfirmsABump) {
  const BumpStream& stream = bumpStream();
  DriftMonitor direct(fieldsafeCamera(), fieldsafeTruth(), fastDrift(), CalibrationConfig{});
  for (const CalibrationPair& p : stream.pairs) direct.addPair(p);

  DriftWatchWorker worker(fieldsafeCamera(), fieldsafeTruth(), fastDrift(), CalibrationConfig{});
  for (std::size_t i = 0; i < stream.pairs.size(); ++i) {
    worker.submit(stream.pairs[i]);
    // Pairs arrive while earlier ones are being tested, sometimes in bursts.
    if (i % 7 == 0) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ASSERT_TRUE(worker.drain(120.0));
  const DriftWatchWorker::Snapshot s = worker.snapshot();
  EXPECT_EQ(s.pairs_seen, 80u);
  EXPECT_EQ(s.queued, 0u);
  EXPECT_FALSE(s.testing);  // ~status's drift_pairs_waiting is 0 once drained
  EXPECT_EQ(s.dropped, 0u);
  EXPECT_TRUE(s.error.empty()) << s.error;
  EXPECT_EQ(s.state, DriftState::kError);
  EXPECT_EQ(s.state, direct.state());
  ASSERT_TRUE(s.candidate);
  ASSERT_TRUE(direct.candidate());
  EXPECT_EQ(s.candidate->extrinsic.rotation_vector, direct.candidate()->extrinsic.rotation_vector);
  EXPECT_EQ(s.candidate->extrinsic.translation, direct.candidate()->extrinsic.translation);
  EXPECT_LT(rotationErrorRad(s.candidate->extrinsic, stream.after), 0.15 * M_PI / 180.0);
  EXPECT_GT(s.tests, 10u);
  EXPECT_GT(s.seconds, 0.0);

  const auto update = worker.accept();
  ASSERT_TRUE(update);
  EXPECT_EQ(update->old_reference.translation, fieldsafeTruth().translation);
  const DriftWatchWorker::Snapshot after = worker.snapshot();
  EXPECT_EQ(after.state, DriftState::kOk);
  EXPECT_EQ(after.reference.rotation_vector, s.candidate->extrinsic.rotation_vector);
  EXPECT_FALSE(worker.accept()) << "nothing left to accept";
}

TEST(DriftWatchWorker, AStableRigStaysOkAndANewReferenceIsTakenBetweenTests) {
  const BumpStream& stream = bumpStream();
  DriftWatchWorker worker(fieldsafeCamera(), fieldsafeTruth(), fastDrift(), CalibrationConfig{});
  for (std::size_t i = 0; i < 40; ++i) worker.submit(stream.pairs[i]);
  ASSERT_TRUE(worker.drain(120.0));
  EXPECT_EQ(worker.snapshot().state, DriftState::kOk);
  EXPECT_EQ(worker.snapshot().tests, 4u);  // at 30, 33, 36, 39 pairs
  worker.setReference(stream.after);
  EXPECT_EQ(worker.snapshot().reference.rotation_vector, stream.after.rotation_vector);
}

TEST(DriftWatchWorker, RefusesABadConfig) {
  DriftConfig bad;
  bad.window_pairs = 2;
  EXPECT_THROW(DriftWatchWorker(fieldsafeCamera(), fieldsafeTruth(), bad, CalibrationConfig{}),
               std::invalid_argument);
}

TEST(DriftWatchWorker, PairsCandidateFramesByAssociationWhenAsked) {
  // The first 12 pairs as kept at frames 0, 10, 20, ..., and frames 5, 15, ... with the same
  // people and a post: candidates the watch pairs at its reference (issue 23).
  const BumpStream& stream = bumpStream();
  std::vector<CalibrationPair> frames;
  for (std::size_t i = 0; i < 12; ++i) {
    CalibrationPair pair = stream.pairs[i];
    pair.candidate_index = 10 * i;
    frames.push_back(pair);
    frames.push_back(test_support::asCandidateWithPost(stream.pairs[i + 12], 10 * i + 5, i % 2 == 0 ? 1.2 : -1.2));
  }
  DriftMonitor direct(fieldsafeCamera(), fieldsafeTruth(), fastDrift(), CalibrationConfig{});
  direct.pairByAssociation(AssociationPairing{});
  for (const CalibrationPair& f : frames) direct.add(f);

  DriftWatchWorker associating(fieldsafeCamera(), fieldsafeTruth(), fastDrift(), CalibrationConfig{}, std::nullopt,
                               AssociationPairing{});
  DriftWatchWorker counting(fieldsafeCamera(), fieldsafeTruth(), fastDrift(), CalibrationConfig{});
  for (const CalibrationPair& f : frames) {
    associating.submit(f);
    counting.submit(f);
  }
  ASSERT_TRUE(associating.drain(120.0));
  ASSERT_TRUE(counting.drain(120.0));
  EXPECT_GE(associating.snapshot().association_pairs, 8u);
  EXPECT_EQ(associating.snapshot().association_pairs, direct.associationPairs());
  EXPECT_EQ(associating.snapshot().pairs_seen, 12u + direct.associationPairs());
  EXPECT_EQ(counting.snapshot().association_pairs, 0u);
  EXPECT_EQ(counting.snapshot().pairs_seen, 12u);
}
