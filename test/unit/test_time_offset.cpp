// The camera time offset as a seventh parameter (issue 21): recovered with the extrinsic from
// pairs whose camera is late or early; the paper mode and mode none ignore it; fixed uses the
// value given; the evaluator moves points by their motion; a steady drive leaves it undecided.

#include "thermal_lidar_calibration/core/calibrator.hpp"
#include "thermal_lidar_calibration/core/person_timing.hpp"
#include "thermal_lidar_calibration/core/timed_refinement.hpp"
#include "thermal_lidar_calibration/core/timing_resolution.hpp"
#include "thermal_lidar_calibration/core/random.hpp"

#include "../support/moving_pairs.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace thermal_lidar_calibration;
using test_support::fieldsafeCamera;
using test_support::fieldsafeTruth;

namespace {

constexpr double kDeg = M_PI / 180.0;

std::vector<CalibrationPair> movingPairs(double delay_s, bool steady = false, int n = 40) {
  test_support::SyntheticPairsOptions o;
  o.pairs = n;
  o.seed = 17;
  o.min_range_m = 5.0;
  o.max_range_m = 16.0;
  auto pairs = test_support::makeSyntheticPairs(fieldsafeCamera(), fieldsafeTruth(), o);
  test_support::MotionOptions m;
  m.delay_s = delay_s;
  m.steady = steady;
  test_support::addMotion(pairs, m);
  return pairs;
}

CalibrationConfig quickConfig(TimeOffsetMode mode) {
  CalibrationConfig c;
  c.algorithm = Algorithm::kPlain;
  c.evolution.population_size = 200;
  c.evolution.max_iterations = 150;
  c.seed = 4;
  c.time_offset.mode = mode;
  return c;
}

}  // namespace

TEST(PersonTiming, PointsMoveWithTheirPersonToTheImagesInstant) {
  CalibrationPair pair;
  pair.stamp_s = 10.0;
  pair.cloud_stamp_s = 9.98;  // the scan 20 ms before the image's stamp
  pair.points = {{10, 0, 0}, {10, 1, 0}};
  pair.labels = {1, 2};
  pair.point_time_s = {0.01f, -0.02f};
  PersonMotion walker;
  walker.label = 2;
  walker.velocity_mps = Eigen::Vector3d(-2, 0, 0);
  walker.scans = 3;
  PersonMotion unmeasured;
  unmeasured.label = 1;
  unmeasured.velocity_mps = Eigen::Vector3d(5, 5, 5);  // not measured (scans 1): ignored
  attachMotion(pair, {unmeasured, walker});
  ASSERT_TRUE(hasMeasuredMotion(pair));
  EXPECT_EQ(pair.point_velocity[0], Eigen::Vector3f::Zero());
  // Point 2 was captured at 9.96; the image at 10.05 (delta 50 ms): 90 ms at -2 m/s.
  EXPECT_NEAR(leadTimeS(pair, 1), 0.04, 1e-9);
  const auto moved = pointsAtImageTime(pair, 0.05);
  EXPECT_NEAR(moved[1].x(), 10.0 - 2 * 0.09, 1e-5);
  EXPECT_EQ(moved[0], pair.points[0]);
  // The evaluator reads the same positions at its offset and at another one.
  CalibrationPair plain = pair;
  plain.point_velocity.clear();
  EXPECT_EQ(pointsAtImageTime(plain, 0.05), plain.points);
}

TEST(PersonTiming, PointsMoveAlongTheGroundOnly) {
  // The centroid's vertical rate is the rings' doing (deskewVelocity): a person's points move
  // with the horizontal part of the fit, in the pair and in the dataset's velocity fields alike.
  CalibrationPair pair;
  pair.stamp_s = pair.cloud_stamp_s = 10.0;
  pair.points = {{12, 1, -0.5f}, {12, 1, 0.5f}};
  pair.labels = {1, 1};
  PersonMotion person;
  person.label = 1;
  person.velocity_mps = Eigen::Vector3d(-2.0, 0.3, 0.25);
  person.scans = 5;
  EXPECT_EQ(deskewVelocity(person), Eigen::Vector3d(-2.0, 0.3, 0.0));
  attachMotion(pair, {person});
  for (const Eigen::Vector3f& v : pair.point_velocity) EXPECT_EQ(v, Eigen::Vector3f(-2.0f, 0.3f, 0.0f));
  const auto moved = pointsAtImageTime(pair, 0.06);
  EXPECT_FLOAT_EQ(moved[0].z(), -0.5f);
  EXPECT_FLOAT_EQ(moved[1].z(), 0.5f);
  EXPECT_NEAR(moved[0].x(), 12.0 - 2.0 * 0.06, 1e-5);
}

TEST(TimeOffset, TheCentroidsVerticalRateDoesNotResolveASteadyDrive) {
  // Straight at one speed past standing people, with each person's fitted vertical rate as the
  // rings make it (+-0.2 m/s about a true 0): that rate differs from person to person, no pose
  // mimics it, and if points moved with it the drive would seem to resolve the offset.
  auto pairs = movingPairs(0.06, true);
  Rng rng(5);
  std::vector<std::size_t> used;
  for (CalibrationPair& pair : pairs) {
    for (PersonMotion& m : pair.motion) m.velocity_mps.z() = rng.uniform(-0.2, 0.2);
    attachMotion(pair, pair.motion);
    used.push_back(used.size());
  }
  const TimingResolution r = timingResolution(fieldsafeCamera(), pairs, used, fieldsafeTruth(), 0.0);
  EXPECT_EQ(r.pairs_with_motion, pairs.size());
  EXPECT_GT(r.resolution_ms, 100.0);
}

TEST(TimeOffset, TheVelocitiesOwnErrorsDoNotResolveASteadyDrive) {
  // The same steady drive, each person's velocity off by up to 30 cm/s horizontally (a walker's
  // swinging arms, a cluster merged for a scan), with the standard error the fit reports for it.
  const auto resolutionOf = [](std::vector<CalibrationPair> pairs, double std_error_mps, double noise_mps) {
    Rng rng(6);
    std::vector<std::size_t> used;
    for (CalibrationPair& pair : pairs) {
      for (PersonMotion& m : pair.motion) {
        m.velocity_mps += Eigen::Vector3d(rng.uniform(-noise_mps, noise_mps), rng.uniform(-noise_mps, noise_mps), 0.0);
        m.std_error_mps.setConstant(std_error_mps);
      }
      attachMotion(pair, pair.motion);
      used.push_back(used.size());
    }
    return timingResolution(fieldsafeCamera(), pairs, used, fieldsafeTruth(), 0.0).resolution_ms;
  };
  const auto steady = movingPairs(0.06, true);
  EXPECT_LT(resolutionOf(steady, 0.0, 0.3), 15.0) << "the errors alone seem to resolve it";
  EXPECT_GT(resolutionOf(steady, 0.2, 0.3), 100.0);
  // A drive with stops, turns and walkers resolves it as before: its people's motions differ
  // by far more than their errors.
  const auto varied = movingPairs(0.06);
  const double known = resolutionOf(varied, 0.0, 0.0);
  EXPECT_LT(known, 5.0);
  EXPECT_NEAR(resolutionOf(varied, 0.2, 0.0), known, 0.1 * known);
}

TEST(TimeOffset, TheEvaluatorAtAnOffsetEqualsTheMovedPoints) {
  const auto pairs = movingPairs(0.06, false, 8);
  const LossEvaluator moving(fieldsafeCamera(), pairs, LossConfig{5.0, PixelRule::kBilinear, 0.0});
  ASSERT_TRUE(moving.hasMotion());
  for (const double delta : {-0.04, 0.0, 0.06}) {
    const LossEvaluator shifted(fieldsafeCamera(), test_support::pairsAtOffset(pairs, delta),
                                LossConfig{5.0, PixelRule::kBilinear});
    EXPECT_NEAR(moving.withTimeOffset(delta).loss(fieldsafeTruth()), shifted.loss(fieldsafeTruth()), 1e-5) << delta;
  }
  // Without an offset the points stay where they were captured.
  const LossEvaluator still(fieldsafeCamera(), pairs, LossConfig{5.0, PixelRule::kBilinear});
  EXPECT_FALSE(still.hasMotion());
  EXPECT_THROW(still.withTimeOffset(0.01), std::logic_error);
  // At the true delay the truth fits better than at zero.
  EXPECT_LT(moving.withTimeOffset(0.06).loss(fieldsafeTruth()), moving.loss(fieldsafeTruth()) - 0.2);
}

TEST(TimeOffset, ALateCameraIsRecoveredWithTheExtrinsic) {
  for (const double delay : {0.06, -0.04}) {
    const auto pairs = movingPairs(delay);
    const CalibrationResult r = calibrate(fieldsafeCamera(), pairs, quickConfig(TimeOffsetMode::kEstimate));
    EXPECT_EQ(r.time_offset_mode, TimeOffsetMode::kEstimate) << r.time_offset_note;
    EXPECT_LT(r.time_resolution_ms, 5.0);
    EXPECT_NEAR(r.time_offset_s, delay, 0.003) << delay;
    EXPECT_LT(rotationErrorRad(r.extrinsic, fieldsafeTruth()), 0.1 * kDeg) << delay;
    EXPECT_LT(translationErrorM(r.extrinsic, fieldsafeTruth()), 0.01) << delay;
    EXPECT_EQ(r.pairs_with_motion, pairs.size());
    EXPECT_FALSE(r.time_offset_profile_s.empty());
    EXPECT_LT(r.loss, r.loss_without_timing);
  }
}

TEST(TimeOffset, IgnoringTheDelayCostsCentimetresAndFixedUsesTheGivenValue) {
  const auto pairs = movingPairs(0.06);
  const CalibrationResult none = calibrate(fieldsafeCamera(), pairs, quickConfig(TimeOffsetMode::kNone));
  EXPECT_EQ(none.time_offset_mode, TimeOffsetMode::kNone);
  EXPECT_EQ(none.time_offset_s, 0.0);
  EXPECT_GT(translationErrorM(none.extrinsic, fieldsafeTruth()), 0.03);
  CalibrationConfig fixed = quickConfig(TimeOffsetMode::kFixed);
  fixed.time_offset.offset_s = 0.06;
  const CalibrationResult known = calibrate(fieldsafeCamera(), pairs, fixed);
  EXPECT_EQ(known.time_offset_mode, TimeOffsetMode::kFixed);
  EXPECT_EQ(known.time_offset_s, 0.06);
  EXPECT_TRUE(known.time_offset_profile_s.empty());
  EXPECT_LT(translationErrorM(known.extrinsic, fieldsafeTruth()), 0.01);
}

TEST(TimeOffset, ThePaperModeAndPairsWithoutMotionIgnoreTiming) {
  auto pairs = movingPairs(0.06, false, 30);
  CalibrationConfig paper = quickConfig(TimeOffsetMode::kEstimate);
  paper.refine.mode = RefineMode::kNone;
  CalibrationConfig none = paper;
  none.time_offset.mode = TimeOffsetMode::kNone;
  const CalibrationResult a = calibrate(fieldsafeCamera(), pairs, paper);
  const CalibrationResult b = calibrate(fieldsafeCamera(), pairs, none);
  EXPECT_EQ(a.time_offset_mode, TimeOffsetMode::kNone);
  EXPECT_NE(a.time_offset_note.find("paper"), std::string::npos) << a.time_offset_note;
  EXPECT_EQ(a.extrinsic.rotation_vector, b.extrinsic.rotation_vector);  // exactly the same run
  EXPECT_EQ(a.extrinsic.translation, b.extrinsic.translation);
  for (auto& p : pairs) p.point_velocity.clear();
  const CalibrationResult c = calibrate(fieldsafeCamera(), pairs, quickConfig(TimeOffsetMode::kEstimate));
  EXPECT_EQ(c.time_offset_mode, TimeOffsetMode::kNone);
  EXPECT_NE(c.time_offset_note.find("motion"), std::string::npos) << c.time_offset_note;
}

TEST(TimeOffset, AnOffsetNotToldFromTheStartKeepsTheStartAndItsPose) {
  // A synchronised camera on a drive that resolves the offset: the joint fit lands a fraction of
  // a millisecond off by chance, within two resolutions of the start, so the run keeps the start
  // and the pose fitted there: the same result as the offset fixed at the start.
  const auto pairs = movingPairs(0.0);
  const CalibrationResult r = calibrate(fieldsafeCamera(), pairs, quickConfig(TimeOffsetMode::kEstimate));
  EXPECT_EQ(r.time_offset_mode, TimeOffsetMode::kEstimate) << r.time_offset_note;
  EXPECT_LT(r.time_resolution_ms, 5.0);
  EXPECT_EQ(r.time_offset_s, 0.0);
  EXPECT_NE(r.time_offset_note.find("not told from it"), std::string::npos) << r.time_offset_note;
  EXPECT_FALSE(r.time_offset_profile_s.empty());  // it was searched all the same
  const CalibrationResult fixed = calibrate(fieldsafeCamera(), pairs, quickConfig(TimeOffsetMode::kFixed));
  EXPECT_EQ(r.extrinsic.rotation_vector, fixed.extrinsic.rotation_vector);
  EXPECT_EQ(r.extrinsic.translation, fixed.extrinsic.translation);
  // With the rule off the joint fit's own answer stands, inside the band the rule would have kept.
  CalibrationConfig joint = quickConfig(TimeOffsetMode::kEstimate);
  joint.time_offset.keep_start_sigmas = 0.0;
  const CalibrationResult j = calibrate(fieldsafeCamera(), pairs, joint);
  EXPECT_EQ(j.time_offset_note.find("not told"), std::string::npos) << j.time_offset_note;
  EXPECT_LT(1000.0 * std::abs(j.time_offset_s), 2.0 * j.time_resolution_ms);
  // A late camera is far outside the band: estimated (ALateCameraIsRecoveredWithTheExtrinsic).
}

TEST(TimeOffset, ASteadyDriveKeepsTheStartingOffsetAndSaysWhy) {
  // Straight at one speed past standing people: a late camera is a camera mounted further
  // forward, so estimating would only trade translation for nothing.
  const auto pairs = movingPairs(0.0, true);
  const CalibrationResult r = calibrate(fieldsafeCamera(), pairs, quickConfig(TimeOffsetMode::kEstimate));
  EXPECT_EQ(r.time_offset_asked, TimeOffsetMode::kEstimate);
  EXPECT_EQ(r.time_offset_mode, TimeOffsetMode::kFixed);
  EXPECT_EQ(r.time_offset_s, 0.0);
  EXPECT_GT(r.time_resolution_ms, 100.0);
  EXPECT_NE(r.time_offset_note.find("not estimated"), std::string::npos) << r.time_offset_note;
  EXPECT_LT(translationErrorM(r.extrinsic, fieldsafeTruth()), 0.01);
  EXPECT_TRUE(r.time_offset_profile_s.empty());
}

TEST(TimeOffset, AnUnresolvedOffsetIsEstimatedOnlyWhenAProbeShowsTheStampsFarOff) {
  // A gate no drive passes: the probe alone decides. 110 ms late (a sweep stamped at its end):
  // the joint refinement moves far and the loss falls, so it is estimated and the note says why.
  CalibrationConfig strict = quickConfig(TimeOffsetMode::kEstimate);
  strict.time_offset.max_resolution_ms = 0.01;
  const auto late = movingPairs(0.11);
  const CalibrationResult r = calibrate(fieldsafeCamera(), late, strict);
  EXPECT_EQ(r.time_offset_mode, TimeOffsetMode::kEstimate) << r.time_offset_note;
  EXPECT_NEAR(r.time_offset_s, 0.11, 0.005);
  EXPECT_NE(r.time_offset_note.find("estimated although"), std::string::npos) << r.time_offset_note;
  // With the probe switched off it stays at its start.
  strict.time_offset.unresolved_min_gain = 1.0;
  const CalibrationResult off = calibrate(fieldsafeCamera(), late, strict);
  EXPECT_EQ(off.time_offset_mode, TimeOffsetMode::kFixed);
  EXPECT_EQ(off.time_offset_s, 0.0);
  // A steady drive 60 ms late: the probe slides along the valley for nothing, never estimated.
  const CalibrationResult steady = calibrate(fieldsafeCamera(), movingPairs(0.06, true), quickConfig(TimeOffsetMode::kEstimate));
  EXPECT_EQ(steady.time_offset_mode, TimeOffsetMode::kFixed) << steady.time_offset_note;
}

TEST(TimeOffset, TheJointRefinementStaysWithinTheRange) {
  const auto pairs = movingPairs(0.06, false, 12);
  const LossEvaluator loss(fieldsafeCamera(), pairs, LossConfig{5.0, PixelRule::kBilinear, 0.0});
  TimeOffsetConfig timing;
  timing.max_s = 0.03;  // the true 60 ms lies outside
  std::vector<std::size_t> all(pairs.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  const TimedRefineOutcome r = TimedRefinement(loss, RefineConfig{}, timing, 1).run(fieldsafeTruth(), 0.0, all);
  EXPECT_LE(std::abs(r.time_offset_s), 0.03 + 1e-12);
  EXPECT_GT(r.time_offset_s, 0.02);  // pushed to the edge nearest the truth
}

TEST(TimeOffset, ASearchNearTheStartFindsTheWholeRangesMinimumForLess) {
  // The association rounds start where an earlier fit's estimate ended: walking the grid downhill
  // from there finds the grid point the whole range finds, with the same pose when the start is
  // that point, and from two steps away it walks there.
  const auto pairs = movingPairs(0.06, false, 20);
  std::vector<std::size_t> all(pairs.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  TimeOffsetConfig timing;
  for (const double start : {0.06, 0.04}) {
    const LossEvaluator loss(fieldsafeCamera(), pairs, LossConfig{5.0, PixelRule::kBilinear, start});
    const TimeOffsetProfile whole = searchTimeOffset(loss, fieldsafeTruth(), all, timing, RefineConfig{}, 1);
    std::vector<std::pair<int, int>> progress;  // (done, total) as a progress line shows them
    const TimeOffsetProfile near = searchTimeOffset(
        loss, fieldsafeTruth(), all, timing, RefineConfig{}, 1,
        [&](int done, int total, double) {
          progress.emplace_back(done, total);
          return true;
        },
        OffsetSearchReach::kNearStart);
    EXPECT_NEAR(whole.offsets_s[whole.best], 0.06, 1e-9) << start;
    EXPECT_NEAR(near.offsets_s[near.best], 0.06, 1e-9) << start;
    EXPECT_LT(near.evaluations, whole.evaluations / 2) << start;
    const long visited = std::count_if(near.losses.begin(), near.losses.end(), [](double v) { return std::isfinite(v); });
    EXPECT_EQ(visited, start == 0.06 ? 3 : 4) << start;  // the start, the steps down, one step up
    // The progress never promises the whole grid and ends complete.
    ASSERT_FALSE(progress.empty());
    for (const auto& [done, total] : progress) EXPECT_LT(total, static_cast<int>(whole.offsets_s.size())) << start;
    EXPECT_EQ(progress.back(), std::make_pair(static_cast<int>(visited), static_cast<int>(visited))) << start;
    if (start == 0.06) {
      EXPECT_EQ(near.poses[near.best].rotation_vector, whole.poses[whole.best].rotation_vector);
      EXPECT_EQ(near.poses[near.best].translation, whole.poses[whole.best].translation);
    }
  }
}
