// The default run's pairing (issue 23): association pairs join after the count rule's first fit
// and the refit keeps to the truth; a wrong initial extrinsic is refused (the paper's fit is run
// instead) and a right one is used; pairing counts is the paper's fit; the skip rule and H_max
// hold for association pairs; one seed, one result, whatever the thread count.
#include "thermal_lidar_calibration/core/association_refit.hpp"

#include "../support/synthetic_pairs.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace thermal_lidar_calibration;
using test_support::fieldsafeCamera;
using test_support::fieldsafeTruth;

namespace {
constexpr double kDeg = M_PI / 180.0;
using test_support::kPostLabel;

std::vector<CalibrationPair> countPairs(int n, std::uint64_t seed) {
  test_support::SyntheticPairsOptions o;
  o.pairs = n;
  o.seed = seed;
  std::vector<CalibrationPair> pairs = test_support::makeSyntheticPairs(fieldsafeCamera(), fieldsafeTruth(), o);
  for (std::size_t i = 0; i < pairs.size(); ++i) pairs[i].candidate_index = 100 * i;
  return pairs;
}

// Frames the count rule rejects: the same kind of people plus a post (test_support).
std::vector<CalibrationPair> candidates(int n, std::uint64_t seed) {
  std::vector<CalibrationPair> frames = countPairs(n, seed);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const double y = (i % 2 == 0 ? 1.0 : -1.0) * (1.0 + 0.1 * static_cast<double>(i % 7));
    frames[i] = test_support::asCandidateWithPost(std::move(frames[i]), 100 * i + 50, y);
  }
  return frames;
}

CalibrationConfig quickConfig() {
  CalibrationConfig config;
  config.evolution.population_size = 200;
  config.evolution.max_iterations = 150;
  config.seed = 4;
  return config;
}

}  // namespace

TEST(AssociationRefit, AddsAssociationPairsWithoutTheExtraClusterAndKeepsToTheTruth) {
  const auto counts = countPairs(30, 8);
  const auto frames = candidates(40, 21);
  const AssociatedCalibration r =
      calibrateWithAssociation(fieldsafeCamera(), counts, frames, quickConfig(), PairingConfig{}, PairingLimits{});
  EXPECT_EQ(r.counts_pairs, 30u);
  EXPECT_GE(r.association_pairs, 30u);  // most frames pair, by the people who are apart
  EXPECT_EQ(r.pairs.size(), r.counts_pairs + r.association_pairs);
  EXPECT_EQ(r.result.pairs_collected, r.pairs.size());
  EXPECT_TRUE(r.converged);
  EXPECT_GE(r.rounds, 2);
  for (std::size_t i = 1; i < r.pairs.size(); ++i) EXPECT_LT(r.pairs[i - 1].candidate_index, r.pairs[i].candidate_index);
  for (const CalibrationPair& p : r.pairs) {
    if (p.rule != PairRule::kAssociation) continue;
    EXPECT_FALSE(p.mask.empty());
    for (std::int32_t label : p.labels) EXPECT_NE(label, kPostLabel);
  }
  EXPECT_LT(rotationErrorRad(r.result.extrinsic, fieldsafeTruth()), 0.2 * kDeg);
  EXPECT_LT(translationErrorM(r.result.extrinsic, fieldsafeTruth()), 0.03);
  EXPECT_GT(r.result.pairs_used, 40u);
}

TEST(AssociationRefit, AWrongInitialExtrinsicIsRefusedAndThePapersFitRecovers) {
  const auto counts = countPairs(30, 8);
  const auto frames = candidates(40, 21);
  InitialExtrinsic wrong;
  wrong.origin = "wrong.yaml";
  // 5 deg about the camera's vertical axis and 30 cm sideways (FieldSAFE's rig).
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(5.0 * kDeg, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const Extrinsic truth = fieldsafeTruth();
  wrong.extrinsic = Extrinsic::fromRotationMatrix(turn * truth.rotationMatrix(),
                                                  truth.translation + Eigen::Vector3d(0.3, 0, 0));
  const AssociatedCalibration r = calibrateWithAssociation(fieldsafeCamera(), counts, frames, quickConfig(),
                                                           PairingConfig{}, PairingLimits{}, wrong);
  EXPECT_FALSE(r.initial_used);
  EXPECT_NE(r.note.find("initial extrinsic wrong.yaml refused"), std::string::npos) << r.note;
  EXPECT_LT(rotationErrorRad(r.result.extrinsic, truth), 0.2 * kDeg);
  EXPECT_LT(translationErrorM(r.result.extrinsic, truth), 0.03);
  EXPECT_GE(r.association_pairs, 30u);

  // Without the check, the association at the wrong start would pair few frames (near people
  // still overlap their region; a post may land on someone): a start to refuse, not to build on.
  const auto paired = [&](const Extrinsic& e) {
    return associatePairs(fieldsafeCamera(), frames, {}, e, std::nullopt, AssociationConfig{}, PairingLimits{}).size();
  };
  EXPECT_LT(4 * paired(wrong.extrinsic), paired(truth));
}

TEST(AssociationRefit, ARightInitialExtrinsicReplacesTheFirstFit) {
  const auto counts = countPairs(30, 8);
  const auto frames = candidates(40, 21);
  InitialExtrinsic right;
  right.origin = "target_chain.yaml";
  right.extrinsic = fieldsafeTruth();
  right.extrinsic.translation.x() += 0.01;
  const AssociatedCalibration r = calibrateWithAssociation(fieldsafeCamera(), counts, frames, quickConfig(),
                                                           PairingConfig{}, PairingLimits{}, right);
  EXPECT_TRUE(r.initial_used) << r.note;
  EXPECT_NE(r.note.find("started from the initial extrinsic target_chain.yaml"), std::string::npos) << r.note;
  EXPECT_EQ(r.result.outlier_fits_accepted, 0);  // no Algorithm 2 ran
  EXPECT_LT(rotationErrorRad(r.result.extrinsic, fieldsafeTruth()), 0.2 * kDeg);
  EXPECT_LT(translationErrorM(r.result.extrinsic, fieldsafeTruth()), 0.03);
}

TEST(AssociationRefit, PairingCountsAndRefineNoneAreThePapersFit) {
  const auto counts = countPairs(30, 8);
  const auto frames = candidates(10, 21);
  CalibrationConfig config = quickConfig();
  PairingConfig pairing;
  pairing.mode = PairingMode::kCounts;
  const AssociatedCalibration r =
      calibrateWithAssociation(fieldsafeCamera(), counts, frames, config, pairing, PairingLimits{});
  const CalibrationResult plain = calibrate(fieldsafeCamera(), counts, config);
  EXPECT_EQ(r.association_pairs, 0u);
  EXPECT_EQ(r.rounds, 0);
  EXPECT_EQ(r.pairs.size(), counts.size());
  EXPECT_EQ(r.result.extrinsic.rotation_vector, plain.extrinsic.rotation_vector);
  EXPECT_EQ(r.result.extrinsic.translation, plain.extrinsic.translation);

  config.refine.mode = RefineMode::kNone;
  const AssociatedCalibration paper =
      calibrateWithAssociation(fieldsafeCamera(), counts, frames, config, PairingConfig{}, PairingLimits{});
  EXPECT_EQ(paper.association_pairs, 0u);
  EXPECT_EQ(paper.result.extrinsic.translation, calibrate(fieldsafeCamera(), counts, config).extrinsic.translation);
}

TEST(AssociationRefit, SkipRuleAndHMaxHoldForAssociationPairs) {
  auto frames = candidates(12, 21);
  for (std::size_t i = 0; i < frames.size(); ++i) frames[i].candidate_index = 10 + i;  // consecutive
  PairingLimits limits;
  limits.skip_frames = 3;
  // A count-rule pair at 12: candidates 13-15 follow it and make no pair.
  const std::vector<CalibrationPair> pairs = associatePairs(fieldsafeCamera(), frames, {12}, fieldsafeTruth(),
                                                            std::nullopt, AssociationConfig{}, limits);
  ASSERT_FALSE(pairs.empty());
  std::uint64_t last = 12;
  bool before_count_pair = false;
  for (const CalibrationPair& p : pairs) {
    if (p.candidate_index < 12) {
      before_count_pair = true;
      continue;
    }
    EXPECT_GT(p.candidate_index, last + 3) << "within the skip of the pair at " << last;
    last = p.candidate_index;
  }
  EXPECT_TRUE(before_count_pair);
  limits.max_people = 1;
  limits.skip_frames = 0;
  for (const CalibrationPair& p : associatePairs(fieldsafeCamera(), frames, {}, fieldsafeTruth(), std::nullopt,
                                                 AssociationConfig{}, limits)) {
    EXPECT_EQ(p.people, 1);
  }
}

TEST(AssociationRefit, OneSeedOneResultWhateverTheThreads) {
  const auto counts = countPairs(25, 8);
  const auto frames = candidates(25, 21);
  CalibrationConfig config = quickConfig();
  config.num_threads = 1;
  const AssociatedCalibration one =
      calibrateWithAssociation(fieldsafeCamera(), counts, frames, config, PairingConfig{}, PairingLimits{});
  config.num_threads = 2;
  const AssociatedCalibration two =
      calibrateWithAssociation(fieldsafeCamera(), counts, frames, config, PairingConfig{}, PairingLimits{});
  EXPECT_EQ(one.result.extrinsic.rotation_vector, two.result.extrinsic.rotation_vector);
  EXPECT_EQ(one.result.extrinsic.translation, two.result.extrinsic.translation);
  EXPECT_EQ(one.association_pairs, two.association_pairs);
  EXPECT_EQ(one.result.inliers, two.result.inliers);
}

TEST(AssociationRefit, BadSettingsAreRefused) {
  PairingConfig pairing;
  pairing.min_initial_agreement = 2.0;
  EXPECT_THROW(pairing.validate(), std::invalid_argument);
  pairing = PairingConfig{};
  pairing.association.max_rounds = 0;
  EXPECT_THROW(pairing.validate(), std::invalid_argument);
}

// The ring alias check (ring_alias.hpp) runs in the first fit and in every refit; the result
// counts them all (a turn kept in an early round moved every later round's start).
TEST(AssociationRefit, TheResultCountsTheRingAliasCheckOfEveryFit) {
  auto counts = countPairs(30, 8);
  auto frames = candidates(40, 21);
  test_support::snapToRings(counts, 4.0 / 3.0);
  test_support::snapToRings(frames, 4.0 / 3.0);
  const AssociatedCalibration r =
      calibrateWithAssociation(fieldsafeCamera(), counts, frames, quickConfig(), PairingConfig{}, PairingLimits{});
  ASSERT_GE(r.association_pairs, 1u);
  EXPECT_NEAR(r.result.ring_spacing_rad / kDeg, 4.0 / 3.0, 0.01);
  // 4 starts (+-1, +-2 spacings) in the first fit and in each refit: the last round refits only
  // when the pairs still changed.
  const int refits = r.converged ? r.rounds - 1 : r.rounds;
  EXPECT_EQ(r.result.ring_alias_tried, 4 * (1 + refits));
  EXPECT_LT(rotationErrorRad(r.result.extrinsic, fieldsafeTruth()), 0.3 * kDeg);  // sane (quick config)
}

namespace {
// The candidate frames of the final round's tests: `spaced` (at 100 i + 50) and beside each of
// them a frame the skip rule passed over (100 i + 51), in stamp order.
std::vector<CalibrationPair> withSkippedBeside(const std::vector<CalibrationPair>& spaced,
                                               std::vector<CalibrationPair> skipped) {
  for (std::size_t i = 0; i < skipped.size(); ++i) {
    skipped[i].candidate_index = 100 * i + 51;  // beside the spaced ones, within skip_frames
    skipped[i].outside_skip_rule = true;
  }
  std::vector<CalibrationPair> frames = spaced;
  frames.insert(frames.end(), skipped.begin(), skipped.end());
  std::sort(frames.begin(), frames.end(), [](const CalibrationPair& a, const CalibrationPair& b) {
    return a.candidate_index < b.candidate_index;
  });
  return frames;
}
}  // namespace

// Issue 24: the frames the skip rule passed over (outside_skip_rule) wait for the final round. The
// rounds never pair them; the final round pairs them at the rounds' extrinsic, marks every pair
// the rounds did not make, and its refinement stays at the truth. Without it they are left alone.
TEST(AssociationRefit, TheFinalRoundPairsTheSkippedFramesAfterTheRoundsAndMarksThem) {
  const auto counts = countPairs(30, 8);
  const std::vector<CalibrationPair> frames = withSkippedBeside(candidates(40, 21), candidates(30, 33));
  const auto beside = [](const CalibrationPair& p) { return p.candidate_index % 100 == 51; };

  PairingConfig without;
  without.final_round = false;
  const AssociatedCalibration rounds_only =
      calibrateWithAssociation(fieldsafeCamera(), counts, frames, quickConfig(), without, PairingLimits{});
  EXPECT_FALSE(rounds_only.final_round);
  EXPECT_EQ(std::count_if(rounds_only.pairs.begin(), rounds_only.pairs.end(), beside), 0);

  const AssociatedCalibration r =
      calibrateWithAssociation(fieldsafeCamera(), counts, frames, quickConfig(), PairingConfig{}, PairingLimits{});
  EXPECT_TRUE(r.final_round);
  EXPECT_EQ(r.rounds, rounds_only.rounds);  // the rounds did not see the skipped frames
  const auto paired_beside = std::count_if(r.pairs.begin(), r.pairs.end(), beside);
  EXPECT_GE(paired_beside, 20);
  std::size_t marked = 0;
  for (const CalibrationPair& p : r.pairs) {
    if (beside(p)) EXPECT_TRUE(p.outside_skip_rule) << p.candidate_index;
    if (p.rule == PairRule::kCounts) EXPECT_FALSE(p.outside_skip_rule) << p.candidate_index;
    marked += p.outside_skip_rule ? 1 : 0;
  }
  EXPECT_EQ(r.final_round_pairs, marked);
  EXPECT_GE(marked, static_cast<std::size_t>(paired_beside));
  EXPECT_EQ(r.pairs.size(), r.counts_pairs + r.association_pairs);
  EXPECT_EQ(r.result.pairs_collected, r.pairs.size());
  for (std::size_t i = 1; i < r.pairs.size(); ++i) EXPECT_LT(r.pairs[i - 1].candidate_index, r.pairs[i].candidate_index);
  EXPECT_LT(rotationErrorRad(r.result.extrinsic, fieldsafeTruth()), 0.2 * kDeg);
  EXPECT_LT(translationErrorM(r.result.extrinsic, fieldsafeTruth()), 0.03);
  EXPECT_GT(r.result.evaluations, rounds_only.result.evaluations);  // the final refinement's work counts
}

// The final round refines without the ring alias check (the rounds ran it); the result still
// reports the rounds' check: how many starts, which turn, and the ring spacing they turned by
// (it used to read 0 deg beside the starts refined).
TEST(AssociationRefit, TheFinalRoundKeepsTheRoundsRingAliasReport) {
  auto counts = countPairs(30, 8);
  auto spaced = candidates(40, 21);
  auto skipped = candidates(30, 33);
  for (auto* pairs : {&counts, &spaced, &skipped}) test_support::snapToRings(*pairs, 4.0 / 3.0);
  const AssociatedCalibration r = calibrateWithAssociation(
      fieldsafeCamera(), counts, withSkippedBeside(spaced, skipped), quickConfig(), PairingConfig{}, PairingLimits{});
  ASSERT_TRUE(r.final_round);
  EXPECT_NEAR(r.result.ring_spacing_rad / kDeg, 4.0 / 3.0, 0.01);
  const int refits = r.converged ? r.rounds - 1 : r.rounds;
  EXPECT_EQ(r.result.ring_alias_tried, 4 * (1 + refits));
}
