// The new extrinsic after a confirmed change (core/drift_update_fit.hpp): after a turn the
// pairs pick the turn about the camera centre, after a shift the shift, after a bump that turns
// and shifts the camera clearly the full pose; monitor_update_full_significance 1 always takes
// the full pose.
#include "thermal_lidar_calibration/core/drift_update_fit.hpp"

#include "../support/synthetic_pairs.hpp"
#include "thermal_lidar_calibration/synthetic/synthetic_rig.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

using namespace thermal_lidar_calibration;
using test_support::fieldsafeCamera;
using synthetic::bumpedExtrinsic;
using test_support::fieldsafeTruth;

namespace {

constexpr double kDeg = M_PI / 180.0;

std::vector<CalibrationPair> pairsSeenWith(const Extrinsic& truth, std::uint64_t seed) {
  test_support::SyntheticPairsOptions o;
  o.pairs = 45;
  o.seed = seed;
  return test_support::makeSyntheticPairs(fieldsafeCamera(), truth, o);
}

CalibrationConfig singleThreaded() {
  CalibrationConfig c;
  c.num_threads = 1;
  return c;
}

}  // namespace

TEST(DriftUpdateFit, AfterATurnTheTurnAboutTheCameraCentre) {
  const Extrinsic before = fieldsafeTruth();
  const Extrinsic after = bumpedExtrinsic(before, Eigen::Vector3d(0.3, -0.8, 0.5), 0.5, Eigen::Vector3d::Zero());
  const DriftUpdateFit u = fitDriftUpdate(fieldsafeCamera(), pairsSeenWith(after, 11), before,
                                          before, DriftConfig{}, singleThreaded());
  EXPECT_EQ(u.model, DriftUpdateModel::kTurn) << "full p " << u.full_p_value;
  EXPECT_GT(u.full_p_value, 0.01);
  EXPECT_LT(rotationErrorRad(u.fit.estimate, after), 0.15 * kDeg);
  // The camera stayed where it was: off only by the turn of t (0.5 deg of ~0.6 m).
  EXPECT_LT(translationErrorM(u.fit.estimate, after), 0.007);
  EXPECT_GT(u.fit.used.size(), 30u);
}

TEST(DriftUpdateFit, AfterAShiftTheShiftWithoutATurn) {
  const Extrinsic before = fieldsafeTruth();
  const Extrinsic after = bumpedExtrinsic(before, Eigen::Vector3d::UnitX(), 0.0, Eigen::Vector3d(0.025, -0.015, 0.006));
  const DriftUpdateFit u = fitDriftUpdate(fieldsafeCamera(), pairsSeenWith(after, 12), before,
                                          before, DriftConfig{}, singleThreaded());
  EXPECT_EQ(u.model, DriftUpdateModel::kShift) << "full p " << u.full_p_value;
  EXPECT_LT(rotationErrorRad(u.fit.estimate, before), 1e-9) << "the camera turned";
  EXPECT_LT(translationErrorM(u.fit.estimate, after), 0.01);
}

TEST(DriftUpdateFit, ABumpThatTurnsAndShiftsClearlyTakesTheFullPose) {
  const Extrinsic before = fieldsafeTruth();
  const Extrinsic after = bumpedExtrinsic(before, Eigen::Vector3d(0.0, 1.0, 0.0), 0.5, Eigen::Vector3d(-0.08, 0.0, 0.0));
  const DriftUpdateFit u = fitDriftUpdate(fieldsafeCamera(), pairsSeenWith(after, 13), before,
                                          before, DriftConfig{}, singleThreaded());
  EXPECT_EQ(u.model, DriftUpdateModel::kFull) << "full p " << u.full_p_value;
  EXPECT_LT(u.full_p_value, 0.01);
  EXPECT_LT(rotationErrorRad(u.fit.estimate, after), 0.15 * kDeg);
  EXPECT_LT(translationErrorM(u.fit.estimate, after), 0.02);
}

TEST(DriftUpdateFit, SignificanceOneAlwaysTakesTheFullPose) {
  const Extrinsic before = fieldsafeTruth();
  const Extrinsic after = bumpedExtrinsic(before, Eigen::Vector3d(0.3, -0.8, 0.5), 0.5, Eigen::Vector3d::Zero());
  DriftConfig config;
  config.update_full_significance = 1.0;
  const DriftUpdateFit u = fitDriftUpdate(fieldsafeCamera(), pairsSeenWith(after, 11), before,
                                          before, config, singleThreaded());
  EXPECT_EQ(u.model, DriftUpdateModel::kFull);
  EXPECT_EQ(u.full_p_value, 0.0);
  EXPECT_STREQ(toString(u.model), "full");
}

TEST(DriftUpdateFit, RefusesTooFewPairsAndABadConfig) {
  const std::vector<CalibrationPair> few = test_support::makeSyntheticPairs(
      fieldsafeCamera(), fieldsafeTruth(), test_support::SyntheticPairsOptions{5, 2, 80, 4.0, 20.0, -1.9, 3});
  EXPECT_THROW(fitDriftUpdate(fieldsafeCamera(), few, fieldsafeTruth(), fieldsafeTruth(),
                              DriftConfig{}, singleThreaded()),
               std::invalid_argument);
  DriftConfig bad;
  bad.update_full_significance = 0.0;
  EXPECT_THROW(bad.validate(), std::invalid_argument);
}
