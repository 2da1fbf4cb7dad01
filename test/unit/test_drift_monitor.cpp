// The drift watch on streams of synthetic pairs (test/support): a rig that stays put must stay
// OK (clean and with realistic mask and range noise), a 0.5 deg turn or a 3 cm shift mid-stream
// must be confirmed within 30 pairs with the new extrinsic near the new truth, the image offset
// test sees a shift too small for the losses, an accepted update makes the new extrinsic the
// reference, and the same input gives the same verdicts.
#include "thermal_lidar_calibration/core/drift_monitor.hpp"

#include "../support/synthetic_pairs.hpp"
#include "thermal_lidar_calibration/synthetic/synthetic_rig.hpp"
#include "thermal_lidar_calibration/core/pose_difference.hpp"
#include "thermal_lidar_calibration/synthetic/noise_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <random>
#include <vector>

using namespace thermal_lidar_calibration;
using test_support::fieldsafeCamera;
using synthetic::bumpedExtrinsic;
using test_support::fieldsafeTruth;

namespace {

constexpr double kDeg = M_PI / 180.0;

// `count` pairs seen with `truth`; with `noisy`, the realistic preset's mask edges (+-2 px) and
// 2 cm range noise.
std::vector<CalibrationPair> pairsSeenWith(const Extrinsic& truth, int count, std::uint64_t seed,
                                           bool noisy) {
  test_support::SyntheticPairsOptions o;
  o.pairs = count;
  o.seed = seed;
  std::vector<CalibrationPair> pairs = test_support::makeSyntheticPairs(fieldsafeCamera(), truth, o);
  if (!noisy) return pairs;
  std::mt19937_64 rng(seed + 1000);
  std::normal_distribution<float> range_noise(0.0f, 0.02f);
  for (CalibrationPair& p : pairs) {
    synthetic::perturbMaskEdges(p.mask, 2, rng);
    for (Eigen::Vector3f& point : p.points) {
      const float range = point.norm();
      point *= (range + range_noise(rng)) / range;
    }
  }
  return pairs;
}

// 90 pairs of a rig that stays at the truth (generated once: the rasterised masks take ~15 ms
// a pair): the stable streams, and the "before" part of the change streams.
const std::vector<CalibrationPair>& stablePairs(bool noisy) {
  static const std::vector<CalibrationPair> clean = pairsSeenWith(fieldsafeTruth(), 90, 21, false);
  static const std::vector<CalibrationPair> with_noise = pairsSeenWith(fieldsafeTruth(), 90, 22, true);
  return noisy ? with_noise : clean;
}

std::vector<CalibrationPair> firstPairs(const std::vector<CalibrationPair>& pairs, std::size_t n) {
  return {pairs.begin(), pairs.begin() + static_cast<long>(n)};
}

struct MonitorRun {
  std::vector<DriftRecord> records;
  std::optional<DriftCandidate> candidate;
  std::optional<double> first_error_stamp;
};

MonitorRun monitor(const std::vector<CalibrationPair>& stream, const Extrinsic& reference,
            int threads = 1, const DriftConfig& drift = {}) {
  CalibrationConfig calibration;
  calibration.num_threads = threads;
  DriftMonitor m(fieldsafeCamera(), reference, drift, calibration);
  MonitorRun run;
  for (const CalibrationPair& p : stream) {
    if (auto r = m.addPair(p)) run.records.push_back(*r);
  }
  run.candidate = m.candidate();
  run.first_error_stamp = m.firstErrorStamp();
  return run;
}

std::vector<CalibrationPair> concatenated(std::vector<CalibrationPair> a,
                                          const std::vector<CalibrationPair>& b) {
  a.insert(a.end(), b.begin(), b.end());
  for (std::size_t i = 0; i < a.size(); ++i) a[i].stamp_s = 100.0 + static_cast<double>(i);
  return a;
}

CalibrationConfig singleThreaded() {
  CalibrationConfig calibration;
  calibration.num_threads = 1;
  return calibration;
}

// The candidate's 95 % intervals hold the new truth on every axis, and are real intervals.
void expectIntervalsHold(const DriftCandidate& candidate, const Extrinsic& truth) {
  ASSERT_TRUE(candidate.uncertainty);
  const Uncertainty& u = *candidate.uncertainty;
  EXPECT_EQ(u.resamples, DriftConfig{}.update_uncertainty_resamples);
  const Eigen::Matrix<double, 6, 1> d = asVector(poseDifference(candidate.extrinsic, truth));
  for (int k = 0; k < 6; ++k) {
    EXPECT_GT(u.halfWidth(k), 0.0) << "axis " << k;
    EXPECT_LE(std::abs(d[k]), u.halfWidth(k)) << "axis " << k << " (rotation deg 0-2, cm 3-5)";
  }
}

// Feeds `stream` to `m`, taking every update as soon as one is ready (~auto_update).
std::vector<DriftUpdate> acceptingEveryUpdate(DriftMonitor& m,
                                              const std::vector<CalibrationPair>& stream) {
  std::vector<DriftUpdate> updates;
  for (const CalibrationPair& p : stream) {
    m.addPair(p);
    if (m.updateReady()) updates.push_back(*m.acceptCandidate());
  }
  return updates;
}

}  // namespace

TEST(DriftMonitor, StaysOkOnAStableRigCleanAndNoisy) {
  for (bool noisy : {false, true}) {
    const MonitorRun run = monitor(stablePairs(noisy), fieldsafeTruth());
    ASSERT_EQ(run.records.size(), 21u);  // (90 - 30) / 3 + 1
    for (const DriftRecord& r : run.records) {
      EXPECT_EQ(r.state, DriftState::kOk) << (noisy ? "noisy" : "clean") << " at pair "
                                          << r.pairs_seen << ": p = " << r.test.p_value;
      EXPECT_EQ(r.test.pairs_in_window, 30u);
    }
    EXPECT_FALSE(run.candidate);
  }
}

TEST(DriftMonitor, ConfirmsAHalfDegreeTurnWithin30PairsAndFitsTheNewTruth) {
  const Extrinsic before = fieldsafeTruth();
  const Extrinsic after = bumpedExtrinsic(before, Eigen::Vector3d(0.3, -0.8, 0.5), 0.5, Eigen::Vector3d::Zero());
  const auto stream = concatenated(firstPairs(stablePairs(false), 45),
                                   pairsSeenWith(after, 63, 32, false));
  const MonitorRun run = monitor(stream, before);
  for (const DriftRecord& r : run.records) {
    if (r.pairs_seen <= 45) EXPECT_EQ(r.state, DriftState::kOk) << "before, at " << r.pairs_seen;
  }
  ASSERT_TRUE(run.first_error_stamp);
  const double pairs_after_change = *run.first_error_stamp - (100.0 + 45.0) + 1.0;
  EXPECT_LE(pairs_after_change, 30.0);
  EXPECT_EQ(run.records.back().state, DriftState::kError);
  // The change is reported as what it is.
  EXPECT_NEAR(run.records.back().test.change.angle_deg, 0.5, 0.1);
  EXPECT_GT(run.records.back().test.loss_reference, 5.0 * run.records.back().test.loss_fit);
  ASSERT_TRUE(run.candidate);
  EXPECT_TRUE(run.candidate->complete);
  EXPECT_NEAR(run.candidate->change_stamp_s, 145.0, 2.0);  // the first pair after the bump
  EXPECT_LT(rotationErrorRad(run.candidate->extrinsic, after), 0.15 * kDeg);
  EXPECT_LT(translationErrorM(run.candidate->extrinsic, after), 0.02);
}

TEST(DriftMonitor, ConfirmsAThreeCentimetreShiftWithin30Pairs) {
  const Extrinsic before = fieldsafeTruth();
  const Extrinsic after = bumpedExtrinsic(before, Eigen::Vector3d::UnitX(), 0.0, Eigen::Vector3d(0.025, -0.015, 0.006));
  const auto stream = concatenated(firstPairs(stablePairs(false), 45),
                                   pairsSeenWith(after, 63, 42, false));
  const MonitorRun run = monitor(stream, before);
  ASSERT_TRUE(run.first_error_stamp);
  EXPECT_LE(*run.first_error_stamp - (100.0 + 45.0) + 1.0, 30.0);
  ASSERT_TRUE(run.candidate);
  EXPECT_LT(rotationErrorRad(run.candidate->extrinsic, after), 0.15 * kDeg);
  EXPECT_LT(translationErrorM(run.candidate->extrinsic, after), 0.02);
  // Intervals come with it (on these exact masks they are narrower than the candidate's few mm
  // of error: they measure what the pairs pin down, not the choice of model).
  ASSERT_TRUE(run.candidate->uncertainty);
  EXPECT_EQ(run.candidate->uncertainty->resamples, DriftConfig{}.update_uncertainty_resamples);
  // Without intervals (monitor_update_uncertainty_resamples 0) the same candidate, bare.
  DriftConfig bare;
  bare.update_uncertainty_resamples = 0;
  const MonitorRun without = monitor(stream, before, 1, bare);
  ASSERT_TRUE(without.candidate);
  EXPECT_FALSE(without.candidate->uncertainty);
  EXPECT_EQ(without.candidate->extrinsic.translation, run.candidate->extrinsic.translation);
  EXPECT_EQ(without.candidate->extrinsic.rotation_vector, run.candidate->extrinsic.rotation_vector);
}

// The offset test on one window: seen against an extrinsic that puts the people 0.8 px to the
// right, the window's offsets say -0.8 px across, significantly; against the truth, nothing.
TEST(DriftMonitor, TheOffsetTestMeasuresHowFarThePeopleMovedInTheImage) {
  const std::vector<CalibrationPair> window = firstPairs(stablePairs(true), 30);
  const Extrinsic off_by = offsetInImage(fieldsafeTruth(), fieldsafeCamera(), Eigen::Vector2d(0.8, 0.0));
  const DriftWindowTest moved =
      testDriftWindow(fieldsafeCamera(), window, off_by, DriftConfig{}, singleThreaded());
  EXPECT_NEAR(moved.offset_px.x(), -0.8, 0.2);
  EXPECT_LT(moved.offset_p_value.x(), 0.001);
  EXPECT_GT(moved.offset_pairs, 20u);
  EXPECT_TRUE(moved.offset_changed);
  EXPECT_TRUE(moved.changed());
  EXPECT_EQ(moved.changed_p_value, moved.significant && moved.large ? moved.p_value
                                                                    : moved.offset_p_value.x());
  const DriftWindowTest stays =
      testDriftWindow(fieldsafeCamera(), window, fieldsafeTruth(), DriftConfig{}, singleThreaded());
  EXPECT_LT(std::abs(stays.offset_px.x()), 0.2);
  EXPECT_FALSE(stays.offset_changed);
  EXPECT_FALSE(stays.changed());
}

// A 2 cm sideways shift with realistic mask-edge noise moves the people about 1 px: the window
// fits' losses cannot tell it from their own wander, the image offsets can. Off (minimum
// offsets out of reach), the watch misses it within 30 pairs; on (the defaults), it confirms it.
TEST(DriftMonitor, TheOffsetTestConfirmsASmallShiftTheLossesMiss) {
  const Extrinsic before = fieldsafeTruth();
  const Extrinsic after = bumpedExtrinsic(before, Eigen::Vector3d::UnitX(), 0.0, Eigen::Vector3d(0.02, 0.0, 0.0));
  const auto stream = concatenated(firstPairs(stablePairs(true), 45),
                                   pairsSeenWith(after, 30, 72, true));
  DriftConfig without_offsets;
  without_offsets.min_offset_x_px = without_offsets.min_offset_y_px = 1e4;
  for (const DriftConfig& config : {without_offsets, DriftConfig{}}) {
    DriftMonitor m(fieldsafeCamera(), before, config, singleThreaded());
    for (const CalibrationPair& p : stream) m.addPair(p);
    const bool offsets_on = config.min_offset_x_px < 100.0;
    EXPECT_EQ(m.firstErrorStamp().has_value(), offsets_on) << (offsets_on ? "on" : "off");
    if (m.firstErrorStamp()) EXPECT_GE(*m.firstErrorStamp(), 145.0);  // after the shift
  }
}

TEST(DriftMonitor, AcceptingAnEarlyUpdateOffersTheFinalOneLater) {
  const Extrinsic before = fieldsafeTruth();
  const Extrinsic after = bumpedExtrinsic(before, Eigen::Vector3d(1.0, 0.2, -0.4), 0.5, Eigen::Vector3d::Zero());
  const auto stream = concatenated(firstPairs(stablePairs(false), 36),
                                   pairsSeenWith(after, 51, 52, false));
  DriftConfig config;
  config.update_pairs = 40;
  DriftMonitor m(fieldsafeCamera(), before, config, singleThreaded());
  const std::vector<DriftUpdate> updates = acceptingEveryUpdate(m, stream);
  ASSERT_EQ(updates.size(), 2u);
  EXPECT_FALSE(updates[0].accepted.complete);  // at the moment of confirmation
  EXPECT_TRUE(updates[1].accepted.complete);   // on update_pairs pairs after the change
  EXPECT_EQ(updates[0].old_reference.translation, before.translation);
  EXPECT_EQ(updates[1].old_reference.translation, updates[0].accepted.extrinsic.translation);
  EXPECT_TRUE(updates[0].accepted.first_error_stamp_s);
  EXPECT_EQ(m.state(), DriftState::kOk);
  EXPECT_LT(rotationErrorRad(m.reference(), after), 0.15 * kDeg);
  EXPECT_LT(translationErrorM(m.reference(), after), 0.02);
  EXPECT_FALSE(m.acceptCandidate());  // nothing left to accept
}

// After an early update the windows that still hold pairs of the old rig are not tested
// against the new reference: those pairs now look changed the other way, and a test on them
// once threw the settling away, so the final fit never came (seen live: 0.27 deg / 3 cm off at
// the end of a drive). The next test waits for a window of pairs since the accepted change,
// and the final update follows.
TEST(DriftMonitor, AfterAnEarlyUpdateTheOldRigsPairsAreNotTestedAgainstIt) {
  const Extrinsic before = fieldsafeTruth();
  const Extrinsic after = bumpedExtrinsic(before, Eigen::Vector3d(-0.4, -0.9, 0.0), 0.5, Eigen::Vector3d::Zero());
  const auto stream = concatenated(firstPairs(stablePairs(false), 45),
                                   pairsSeenWith(after, 63, 82, false));
  DriftConfig config;
  config.update_pairs = 45;
  DriftMonitor m(fieldsafeCamera(), before, config, singleThreaded());
  std::vector<DriftUpdate> updates;
  std::vector<std::uint64_t> tested_after_first_update;
  for (const CalibrationPair& p : stream) {
    const std::optional<DriftRecord> r = m.addPair(p);
    if (r && !updates.empty()) tested_after_first_update.push_back(r->pairs_seen);
    if (m.updateReady()) updates.push_back(*m.acceptCandidate());
  }
  ASSERT_GE(updates.size(), 2u);
  EXPECT_FALSE(updates.front().accepted.complete);
  EXPECT_TRUE(updates.back().accepted.complete);
  // concatenated() stamps pair i at 100 + i: the first pair after the accepted change is pair
  // change_stamp - 100, and a window of 30 since it is full when pairs_seen reaches that + 30.
  const double first_after = updates.front().accepted.change_stamp_s - 100.0;
  ASSERT_FALSE(tested_after_first_update.empty());
  for (std::uint64_t seen : tested_after_first_update) {
    EXPECT_GE(static_cast<double>(seen), first_after + 30.0);
  }
  EXPECT_LT(rotationErrorRad(m.reference(), after), 0.15 * kDeg);
  EXPECT_LT(translationErrorM(m.reference(), after), 0.02);
}

// After an accepted change, a later one is placed among the pairs since the accepted change
// only: here the rig turns, the early update is taken, and the bracket then seats back. The
// pairs before the first change fit the seated-back rig too; a split among them would hand the
// second fit the turned rig's pairs in between (seen live: an early update 8 cm off, refitted
// from pairs back to the start of the drive).
TEST(DriftMonitor, ALaterChangeIsPlacedAfterTheAcceptedOne) {
  const Extrinsic before = fieldsafeTruth();
  const Extrinsic after = bumpedExtrinsic(before, Eigen::Vector3d(1.0, 0.2, -0.4), 0.5, Eigen::Vector3d::Zero());
  const std::vector<CalibrationPair> turned = pairsSeenWith(after, 30, 52, false);
  const std::vector<CalibrationPair> seated_back = pairsSeenWith(before, 60, 53, false);
  const auto stream = concatenated(concatenated(firstPairs(stablePairs(false), 60), turned),
                                   seated_back);
  DriftConfig config;
  config.update_pairs = 100;  // keeps the pairs from before the first change in memory
  DriftMonitor m(fieldsafeCamera(), before, config, singleThreaded());
  const std::vector<DriftUpdate> updates = acceptingEveryUpdate(m, stream);
  ASSERT_GE(updates.size(), 2u);
  const double second_change_s = 100.0 + 60.0 + 30.0;  // concatenated() stamps pair i at 100 + i
  EXPECT_NEAR(updates[0].accepted.change_stamp_s, 160.0, 2.0);
  EXPECT_NEAR(updates.back().accepted.change_stamp_s, second_change_s, 2.0);
  EXPECT_LT(rotationErrorRad(m.reference(), before), 0.15 * kDeg);
}

// A change beyond monitor_max_update_*: confirmed (ERROR), but no new extrinsic is offered, so
// auto-update can never publish a fit that wandered off (seen on a realistic-noise drive: a
// 0.5 deg bump refitted to 172 deg and 75 m on windows that could not pin the pose down).
TEST(DriftMonitor, NeverOffersANewExtrinsicBeyondTheUpdateBounds) {
  const Extrinsic before = fieldsafeTruth();
  const Extrinsic after = bumpedExtrinsic(before, Eigen::Vector3d(0.3, -0.8, 0.5), 0.5, Eigen::Vector3d::Zero());
  const auto stream = concatenated(firstPairs(stablePairs(false), 45),
                                   pairsSeenWith(after, 63, 32, false));
  DriftConfig config;
  config.max_update_rotation_deg = 0.3;  // the 0.5 deg bump counts as too large to refit
  CalibrationConfig calibration;
  calibration.num_threads = 1;
  DriftMonitor m(fieldsafeCamera(), before, config, calibration);
  bool ever_ready = false;
  for (const CalibrationPair& p : stream) {
    m.addPair(p);
    ever_ready = ever_ready || m.updateReady() || m.candidate().has_value();
  }
  EXPECT_EQ(m.state(), DriftState::kError);
  EXPECT_FALSE(ever_ready);
  EXPECT_GT(m.candidatesRefused(), 0u);
  EXPECT_FALSE(m.acceptCandidate());
}

TEST(DriftMonitor, SameInputSameVerdictsWhateverTheThreadCount) {
  const Extrinsic before = fieldsafeTruth();
  const Extrinsic after = bumpedExtrinsic(before, Eigen::Vector3d(0.0, 1.0, 0.0), 0.5, Eigen::Vector3d::Zero());
  const auto stream = concatenated(firstPairs(stablePairs(true), 30),
                                   pairsSeenWith(after, 27, 62, true));
  const MonitorRun one = monitor(stream, before, 1);
  const MonitorRun again = monitor(stream, before, 1);
  const MonitorRun two = monitor(stream, before, 2);
  ASSERT_EQ(one.records.size(), again.records.size());
  ASSERT_EQ(one.records.size(), two.records.size());
  for (std::size_t i = 0; i < one.records.size(); ++i) {
    for (const MonitorRun* other : {&again, &two}) {
      const DriftRecord& a = one.records[i];
      const DriftRecord& b = other->records[i];
      EXPECT_EQ(a.state, b.state);
      EXPECT_EQ(a.test.p_value, b.test.p_value);
      EXPECT_EQ(a.test.fit.rotation_vector, b.test.fit.rotation_vector);
      EXPECT_EQ(a.test.fit.translation, b.test.fit.translation);
      EXPECT_EQ(a.test.loss_fit, b.test.loss_fit);
      EXPECT_EQ(a.test.offset_px, b.test.offset_px);
      EXPECT_EQ(a.test.offset_p_value, b.test.offset_p_value);
    }
  }
  ASSERT_TRUE(one.candidate && one.candidate->uncertainty);
  for (const MonitorRun* other : {&again, &two}) {
    ASSERT_TRUE(other->candidate && other->candidate->uncertainty);
    EXPECT_EQ(one.candidate->extrinsic.rotation_vector, other->candidate->extrinsic.rotation_vector);
    EXPECT_EQ(one.candidate->uncertainty->rotation_deg, other->candidate->uncertainty->rotation_deg);
    EXPECT_EQ(one.candidate->uncertainty->translation_cm, other->candidate->uncertainty->translation_cm);
  }
  // With mask-edge and range noise (what the intervals are for), they hold the new truth.
  expectIntervalsHold(*one.candidate, after);
}

TEST(DriftMonitor, TestsEveryPeriodOnceTheWindowIsFull) {
  DriftConfig config;
  config.window_pairs = 12;
  config.period_pairs = 4;
  config.folds = 3;
  CalibrationConfig calibration;
  calibration.num_threads = 1;
  DriftMonitor m(fieldsafeCamera(), fieldsafeTruth(), config, calibration);
  std::vector<std::uint64_t> tested_at;
  for (const CalibrationPair& p : firstPairs(stablePairs(false), 24)) {
    if (auto r = m.addPair(p)) tested_at.push_back(r->pairs_seen);
  }
  EXPECT_EQ(tested_at, (std::vector<std::uint64_t>{12, 16, 20, 24}));
  EXPECT_EQ(m.pairsInWindow(), 12u);
}

TEST(DriftMonitor, RefusesABadConfig) {
  DriftConfig config;
  config.period_pairs = 0;
  EXPECT_THROW(DriftMonitor(fieldsafeCamera(), fieldsafeTruth(), config, CalibrationConfig{}),
               std::invalid_argument);
  config = DriftConfig{};
  config.significance = 0.0;
  EXPECT_THROW(config.validate(), std::invalid_argument);
  config = DriftConfig{};
  config.min_offset_x_px = -0.1;
  EXPECT_THROW(config.validate(), std::invalid_argument);
}
