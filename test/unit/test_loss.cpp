// Hand-computed psi (Eq. 2) and Eq. (1)/(3) cases.
#include "thermal_lidar_calibration/core/loss.hpp"
#include "thermal_lidar_calibration/core/person_timing.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

using namespace thermal_lidar_calibration;

namespace {

// 100 x 80 pinhole camera, f = 100, principal point (50, 40); the only person pixel is (60, 40).
CameraModel smallCamera(std::vector<double> d = {}) {
  return CameraModel::fromK(100, 80, {100, 0, 50, 0, 100, 40, 0, 0, 1}, d);
}

CalibrationPair pairWith(std::vector<Eigen::Vector3f> points) {
  CalibrationPair p;
  p.mask = cv::Mat::zeros(80, 100, CV_8UC1);
  p.mask.at<std::uint8_t>(40, 60) = 1;
  p.points = std::move(points);
  p.labels.assign(p.points.size(), 1);
  return p;
}

double psi(const Eigen::Vector3f& point, const CameraModel& camera = smallCamera(),
           PixelRule rule = PixelRule::kNearest) {
  const LossEvaluator loss(camera, {pairWith({point})}, LossConfig{5.0, rule});
  return loss.pairLoss(0, Extrinsic{});  // identity: LiDAR frame = camera frame
}

}  // namespace

TEST(Psi, OnAPersonPixelIsZero) { EXPECT_DOUBLE_EQ(psi({0.1f, 0.0f, 1.0f}), 0.0); }

TEST(Psi, InsideTheImageIsTheL1DistanceToTheNearestPersonPixel) {
  EXPECT_DOUBLE_EQ(psi({0.0f, 0.0f, 1.0f}), 10.0);         // (50, 40)
  EXPECT_DOUBLE_EQ(psi({0.0f, 0.1f, 2.0f}), 10.0 + 5.0);   // (50, 45)
}

TEST(Psi, OffTheImageOnEachSideAndAtCornersIsTheExactL1Distance) {
  // u = 100 x / z + 50, v = 100 y / z + 40; the person pixel is (60, 40).
  EXPECT_DOUBLE_EQ(psi({-0.7f, 0.0f, 1.0f}), 80.0);              // left: u = -20
  EXPECT_DOUBLE_EQ(psi({1.0f, 0.0f, 1.0f}), 90.0);               // right: u = 150
  EXPECT_DOUBLE_EQ(psi({0.1f, -0.9f, 1.0f}), 90.0);              // top: v = -50
  EXPECT_DOUBLE_EQ(psi({0.1f, 0.9f, 1.0f}), 90.0);               // bottom: v = 130
  EXPECT_DOUBLE_EQ(psi({-1.0f, -1.0f, 1.0f}), 110.0 + 100.0);    // top-left corner (-50, -60)
  EXPECT_DOUBLE_EQ(psi({2.0f, 2.0f, 1.0f}), 190.0 + 200.0);      // bottom-right (250, 240)
}

TEST(Psi, BehindTheCameraScoresC1TimesTheLargerSide) {
  EXPECT_DOUBLE_EQ(psi({0.1f, 0.0f, -1.0f}), 5.0 * 100.0);
  EXPECT_DOUBLE_EQ(psi({0.1f, 0.0f, 0.0f}), 5.0 * 100.0);  // z = 0 is not in front
}

// Beyond the paper (the vertical centring's loss): a margin takes that much off every point in
// front of the camera, down to zero, and leaves the behind-camera penalty alone.
TEST(Psi, AMarginTakesThatMuchOffEachPointInFrontDownToZero) {
  const auto with_margin = [](const Eigen::Vector3f& point, double margin) {
    LossConfig config{5.0, PixelRule::kBilinear};
    config.margin_px = margin;
    const LossEvaluator loss(smallCamera(), {pairWith({point})}, config);
    return loss.pairLoss(0, Extrinsic{});
  };
  EXPECT_DOUBLE_EQ(with_margin({0.0f, 0.0f, 1.0f}, 1.0), 9.0);     // (50, 40): 10 px away
  EXPECT_NEAR(with_margin({0.095f, 0.0f, 1.0f}, 1.0), 0.0, 1e-6);  // (59.5, 40): 0.5 px away
  EXPECT_NEAR(with_margin({0.085f, 0.0f, 1.0f}, 1.0), 0.5, 1e-5);  // (58.5, 40): 1.5 px away
  EXPECT_DOUBLE_EQ(with_margin({0.1f, 0.0f, -1.0f}, 1.0), 5.0 * 100.0);
  const LossEvaluator plain(smallCamera(), {pairWith({{0.0f, 0.0f, 1.0f}})},
                            LossConfig{5.0, PixelRule::kBilinear});
  EXPECT_DOUBLE_EQ(plain.withMargin(2.5).pairLoss(0, Extrinsic{}), 7.5);  // shares the maps
  EXPECT_DOUBLE_EQ(plain.pairLoss(0, Extrinsic{}), 9.5);  // the outline's half pixel only
  EXPECT_THROW(plain.withMargin(-1.0), std::invalid_argument);
}

// Beyond the paper: the sub-pixel rule reads the distance from the person pixels' outline, half a
// pixel beyond their centres, so a point on a person's outline costs nothing at the true pose
// (the mask marks the pixels whose centre a person covers: the outline lies between the last
// person pixel's centre and the next pixel's). The paper's rule is unchanged.
TEST(Psi, TheSubPixelRuleReadsFromThePersonPixelsOutline) {
  const auto read = [](const Eigen::Vector3f& point, double outline, PixelRule rule) {
    LossConfig config{5.0, rule};
    config.outline_px = outline;
    const LossEvaluator loss(smallCamera(), {pairWith({point})}, config);
    return loss.pairLoss(0, Extrinsic{});
  };
  // (60.5, 40): on the edge of the person pixel (60, 40); (61, 40): half a pixel beyond it.
  EXPECT_NEAR(read({0.105f, 0.0f, 1.0f}, 0.5, PixelRule::kBilinear), 0.0, 1e-6);
  EXPECT_NEAR(read({0.105f, 0.0f, 1.0f}, 0.0, PixelRule::kBilinear), 0.5, 1e-5);
  EXPECT_NEAR(read({0.11f, 0.0f, 1.0f}, 0.5, PixelRule::kBilinear), 0.5, 1e-5);
  EXPECT_NEAR(read({0.0f, 0.0f, 1.0f}, 0.5, PixelRule::kBilinear), 9.5, 1e-5);   // (50, 40)
  EXPECT_DOUBLE_EQ(read({0.0f, 0.0f, 1.0f}, 0.5, PixelRule::kNearest), 10.0);    // the paper's
  EXPECT_DOUBLE_EQ(read({0.1f, 0.0f, -1.0f}, 0.5, PixelRule::kBilinear), 5.0 * 100.0);
  // A margin counts from the centres: the larger of the two applies, they do not add up.
  LossConfig config{5.0, PixelRule::kBilinear};
  const LossEvaluator loss(smallCamera(), {pairWith({{0.0f, 0.0f, 1.0f}})}, config);
  EXPECT_DOUBLE_EQ(loss.withMargin(1.0).pairLoss(0, Extrinsic{}), 9.0);
  EXPECT_DOUBLE_EQ(loss.withMargin(0.2).pairLoss(0, Extrinsic{}), 9.5);
  EXPECT_DOUBLE_EQ(loss.withOutline(0.0).pairLoss(0, Extrinsic{}), 10.0);  // shares the maps
  EXPECT_THROW(loss.withOutline(-0.5), std::invalid_argument);
}

TEST(Psi, AMarginAndATimeOffsetCombineInEitherOrder) {
  // The point moves 1 m/s along x: at delta = 0.05 s it projects to (55, 40), 5 px away.
  CalibrationPair pair = pairWith({{0.0f, 0.0f, 1.0f}});
  pair.point_velocity = {{1.0f, 0.0f, 0.0f}};
  const LossEvaluator timed(smallCamera(), {pair}, LossConfig{5.0, PixelRule::kBilinear, 0.0});
  EXPECT_NEAR(timed.withTimeOffset(0.05).pairLoss(0, Extrinsic{}), 4.5, 1e-4);  // outline 0.5
  EXPECT_NEAR(timed.withTimeOffset(0.05).withMargin(1.0).pairLoss(0, Extrinsic{}), 4.0, 1e-4);
  EXPECT_NEAR(timed.withMargin(1.0).withTimeOffset(0.05).pairLoss(0, Extrinsic{}), 4.0, 1e-4);
  EXPECT_NEAR(timed.withMargin(1.0).pairLoss(0, Extrinsic{}), 9.0, 1e-4);  // still at delta 0
  EXPECT_NEAR(timed.withTimeOffset(0.05).withOutline(0.0).pairLoss(0, Extrinsic{}), 5.0, 1e-4);
}

TEST(Psi, ATurningPairsPointsMoveAsTheyDoAtTheImagesInstant) {
  // With a turn rate the points move on p + v T + a T^2 / 2 (a = w (v_y, -v_x, 0)); the evaluator
  // moved to an offset must read exactly what the points moved there by pointsAtImageTime read.
  CalibrationPair pair = pairWith({{0.0f, 0.0f, 1.0f}, {0.02f, 0.01f, 1.0f}});
  pair.labels = {1, 1};
  pair.point_velocity = {{2.0f, 1.0f, 0.0f}, {2.0f, 1.0f, 0.0f}};
  pair.point_time_s = {-0.05f, -0.04f};
  pair.turn_rate_rps = 3.0;  // a large turn, so the bend is many pixels
  const LossEvaluator timed(smallCamera(), {pair}, LossConfig{5.0, PixelRule::kBilinear, 0.0});
  for (const double delta : {-0.04, 0.0, 0.06, 0.11}) {
    CalibrationPair moved = pair;
    moved.points = pointsAtImageTime(pair, delta);
    moved.point_velocity.clear();
    const LossEvaluator at(smallCamera(), {moved}, LossConfig{5.0, PixelRule::kBilinear});
    EXPECT_NEAR(timed.withTimeOffset(delta).pairLoss(0, Extrinsic{}), at.pairLoss(0, Extrinsic{}), 1e-3) << delta;
  }
  // And the bend is there: without the turn the points read elsewhere.
  CalibrationPair straight = pair;
  straight.turn_rate_rps = 0.0;
  const LossEvaluator lines(smallCamera(), {straight}, LossConfig{5.0, PixelRule::kBilinear, 0.0});
  EXPECT_GT(std::abs(lines.withTimeOffset(0.11).pairLoss(0, Extrinsic{}) -
                     timed.withTimeOffset(0.11).pairLoss(0, Extrinsic{})),
            0.5);
}

TEST(Psi, FarAwayProjectionsStayFinite) {
  const double v = psi({1.0f, 0.0f, 1e-30f});
  EXPECT_TRUE(std::isfinite(v));
  EXPECT_GT(v, 5.0 * 100.0);
}

TEST(Psi, DistortionIsAppliedWhenProjecting) {
  const CameraModel camera = smallCamera({-0.2, 0.05, 0.001, -0.002, 0.0});
  const Eigen::Vector3f p(0.3f, 0.2f, 1.0f);
  const Eigen::Vector2d uv = camera.project(p.cast<double>());
  const double expected = std::abs(std::floor(uv.x() + 0.5) - 60) + std::abs(std::floor(uv.y() + 0.5) - 40);
  EXPECT_NEAR(psi(p, camera), expected, 1e-9);
  EXPECT_NE(psi(p, camera), psi(p));  // not the pinhole answer
}

TEST(Psi, BilinearRuleIsContinuous) {
  EXPECT_NEAR(psi({0.055f, 0.0f, 1.0f}, smallCamera(), PixelRule::kBilinear), 4.0, 1e-5);  // 4.5 - 0.5
  EXPECT_NEAR(psi({0.056f, 0.0f, 1.0f}, smallCamera(), PixelRule::kBilinear), 3.9, 1e-4);
  EXPECT_NEAR(psi({0.055f, 0.0f, 1.0f}, smallCamera(), PixelRule::kNearest), 4.0, 1e-9);
}

TEST(Loss, Equation1IsTheMeanOverPointsAndEquation3TheMeanOverPairs) {
  const CameraModel camera = smallCamera();
  const std::vector<CalibrationPair> pairs{pairWith({{0.1f, 0, 1}, {0, 0, 1}}),       // 0, 10
                                           pairWith({{0.1f, 0, -1}, {0.1f, 0, 1}})};  // 500, 0
  const LossEvaluator loss(camera, pairs, LossConfig{});
  EXPECT_DOUBLE_EQ(loss.pairLoss(0, Extrinsic{}), 5.0);
  EXPECT_DOUBLE_EQ(loss.pairLoss(1, Extrinsic{}), 250.0);
  EXPECT_DOUBLE_EQ(loss.loss(Extrinsic{}), 127.5);
  EXPECT_DOUBLE_EQ(loss.loss(Extrinsic{}, {1}), 250.0);
  // The extrinsic moves points: t = (-0.1, 0, 0) shifts u by -10 px at z = 1.
  Extrinsic shift;
  shift.translation = Eigen::Vector3d(-0.1, 0, 0);
  EXPECT_DOUBLE_EQ(loss.pairLoss(0, shift), (10.0 + 20.0) / 2.0);
}

TEST(Loss, BatchEqualsSingleAndDoesNotDependOnThreads) {
  const CameraModel camera = CameraModel::fromK(100, 80, {100, 0, 50, 0, 100, 40, 0, 0, 1},
                                                {-0.1, 0.02, 0, 0, 0});
  std::vector<Eigen::Vector3f> pts;
  for (int i = 0; i < 37; ++i) pts.emplace_back(0.01f * i - 0.2f, 0.005f * i - 0.1f, 1.0f + 0.1f * i);
  const LossEvaluator loss(camera, {pairWith(pts), pairWith(pts)}, LossConfig{});
  std::vector<Extrinsic> candidates;
  for (int i = 0; i < 100; ++i) {
    Extrinsic e;
    e.rotation_vector = Eigen::Vector3d(0.01 * i, -0.003 * i, 0.002 * i);
    e.translation = Eigen::Vector3d(0.001 * i, 0, -0.002 * i);
    candidates.push_back(e);
  }
  std::vector<double> one, two;
  loss.lossBatch(candidates, {}, one, 1);
  loss.lossBatch(candidates, {}, two, 2);
  ASSERT_EQ(one.size(), candidates.size());
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    EXPECT_EQ(one[i], two[i]);
    EXPECT_EQ(one[i], loss.loss(candidates[i]));
  }
}

// The vertical centring's region counts the pairs that leave the margin: per candidate, the pairs
// of the subset (duplicates counted) whose Eq. (1) is above the level, as pairLoss says one by one.
TEST(Loss, PairsAboveCountsWhatPairLossSaysWithAnyThreadCount) {
  const CameraModel camera = smallCamera();
  // At the identity pair 0's point lies 5 px left of the person pixel, pair 1's 240 px right; the
  // candidates move both right by 0.2 px each.
  const std::vector<CalibrationPair> pairs = {pairWith({{0.05, 0, 1}}), pairWith({{2.5, 0, 1}})};
  const LossEvaluator loss(camera, pairs, LossConfig{});
  std::vector<Extrinsic> candidates(40);
  for (std::size_t i = 0; i < candidates.size(); ++i) candidates[i].translation.x() = 0.002 * i;
  const std::vector<std::size_t> subset = {0, 1, 1};
  std::vector<double> one, two;
  loss.pairsAboveBatch(candidates, subset, 3.0, one, 1);
  loss.pairsAboveBatch(candidates, subset, 3.0, two, 2);
  ASSERT_EQ(one.size(), candidates.size());
  std::set<double> seen;
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    double expected = 0.0;
    for (std::size_t i : subset) expected += loss.pairLoss(i, candidates[c]) > 3.0 ? 1.0 : 0.0;
    EXPECT_EQ(one[c], expected) << "candidate " << c;
    EXPECT_EQ(two[c], expected) << "candidate " << c;
    seen.insert(expected);
  }
  EXPECT_EQ(seen, (std::set<double>{2.0, 3.0})) << "pair 0 comes within the level along the way";
}

TEST(Loss, RejectsAMaskThatDisagreesWithTheCamera) {
  CalibrationPair p = pairWith({{0, 0, 1}});
  p.mask = cv::Mat::ones(10, 10, CV_8UC1);
  EXPECT_THROW(LossEvaluator(smallCamera(), {p}, LossConfig{}), std::invalid_argument);
}

TEST(Loss, RejectsImagesTooLargeForTheKernelsFloatIndices) {
  // 4096 x 4096 = 2^24 pixels: float pixel indices would no longer be exact.
  const CameraModel huge = CameraModel::fromK(4096, 4096, {1000, 0, 2048, 0, 1000, 2048, 0, 0, 1}, {});
  CalibrationPair p;
  p.mask = cv::Mat::zeros(4096, 4096, CV_8UC1);
  p.mask.at<std::uint8_t>(10, 10) = 1;
  p.points = {{0, 0, 1}};
  p.labels = {1};
  try {
    LossEvaluator loss(huge, {p}, LossConfig{});
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("4096x4096"), std::string::npos) << e.what();
  }
}

TEST(Loss, InsideFractionCountsPointsLandingInTheImage) {
  const LossEvaluator loss(smallCamera(), {pairWith({{0, 0, 1}, {5, 0, 1}, {0, 0, -1}, {0.1f, 0.1f, 1}})},
                           LossConfig{});
  EXPECT_DOUBLE_EQ(loss.insideFraction(0, Extrinsic{}), 0.5);
}
