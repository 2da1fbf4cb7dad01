// The image offset of a pair (core/image_offset.hpp): the pan/tilt that centres its LiDAR points
// in its mask. Against an extrinsic that puts the points d px off, the offset is -d; a mask a
// few pixels wider than the person (segmentation noise) leaves the offset centred, where a
// search from the extrinsic would stop at the near end of the flat loss; the same answer
// whatever the thread count.
#include "thermal_lidar_calibration/core/image_offset.hpp"

#include "../support/synthetic_pairs.hpp"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include <stdexcept>
#include <vector>

using namespace thermal_lidar_calibration;
using test_support::fieldsafeCamera;
using test_support::fieldsafeTruth;

namespace {

std::vector<CalibrationPair> pairs(int count, std::uint64_t seed) {
  test_support::SyntheticPairsOptions o;
  o.pairs = count;
  o.seed = seed;
  return test_support::makeSyntheticPairs(fieldsafeCamera(), fieldsafeTruth(), o);
}

LossEvaluator bilinearOn(const std::vector<CalibrationPair>& p) {
  return LossEvaluator(fieldsafeCamera(), p, LossConfig{5.0, PixelRule::kBilinear});
}

}  // namespace

TEST(ImageOffset, OffsetInImageMovesThePeopleByThatMuch) {
  const CameraModel camera = fieldsafeCamera(false);
  const Extrinsic truth = fieldsafeTruth();
  const Extrinsic moved = offsetInImage(truth, camera, Eigen::Vector2d(2.0, -1.5));
  // A point 10 m ahead near the optical axis.
  const Eigen::Vector3d p_camera(0.1, -0.2, 10.0);
  const Eigen::Isometry3d T = truth.T_camera_lidar();
  const Eigen::Vector3d p_lidar = T.inverse() * p_camera;
  const Eigen::Vector2d shift =
      camera.project(moved.T_camera_lidar() * p_lidar) - camera.project(p_camera);
  EXPECT_NEAR(shift.x(), 2.0, 0.02);
  EXPECT_NEAR(shift.y(), -1.5, 0.02);
  EXPECT_LT(translationErrorM(offsetInImage(truth, camera, Eigen::Vector2d::Zero()), truth), 1e-12);
}

TEST(ImageOffset, IsMinusTheOffsetTheExtrinsicPutsThePointsAt) {
  // These pairs' points are a random sparse sample of each person, so a pair's own offset at
  // the truth is near zero across the image but can be a few pixels down it (the points need
  // not reach the head and feet); an extrinsic that moves the points by `off` moves it by -off.
  const std::vector<CalibrationPair> p = pairs(8, 3);
  const LossEvaluator bilinear = bilinearOn(p);
  const Eigen::Vector2d off(1.5, -2.0);
  const Extrinsic shifted = offsetInImage(fieldsafeTruth(), fieldsafeCamera(), off);
  Eigen::Vector2d mean_at_truth = Eigen::Vector2d::Zero();
  for (std::size_t i = 0; i < p.size(); ++i) {
    const ImageOffset at_truth = pairImageOffset(bilinear, i, fieldsafeTruth());
    EXPECT_NEAR(at_truth.offset_px.x(), 0.0, 0.5) << "pair " << i;
    EXPECT_NEAR(at_truth.offset_px.y(), 0.0, 3.0) << "pair " << i;
    EXPECT_LT(at_truth.loss_px, 0.2) << "pair " << i;
    mean_at_truth += at_truth.offset_px / static_cast<double>(p.size());
    const ImageOffset o = pairImageOffset(bilinear, i, shifted);
    EXPECT_NEAR(o.offset_px.x() - at_truth.offset_px.x(), -off.x(), 0.2) << "pair " << i;
    EXPECT_NEAR(o.offset_px.y() - at_truth.offset_px.y(), -off.y(), 0.2) << "pair " << i;
  }
  EXPECT_NEAR(mean_at_truth.x(), 0.0, 0.2);
  EXPECT_NEAR(mean_at_truth.y(), 0.0, 1.5);
}

TEST(ImageOffset, AWiderMaskLeavesTheOffsetCentred) {
  // Every mask 3 px wider than the person: the loss is zero over a 6 px wide range of offsets;
  // its middle is still where the person is.
  std::vector<CalibrationPair> p = pairs(8, 4);
  for (CalibrationPair& pair : p) {
    cv::dilate(pair.mask, pair.mask,
               cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(7, 7)));
  }
  const LossEvaluator bilinear = bilinearOn(p);
  const Eigen::Vector2d off(-1.0, 0.0);
  const Extrinsic shifted = offsetInImage(fieldsafeTruth(), fieldsafeCamera(), off);
  double mean_x = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const ImageOffset o = pairImageOffset(bilinear, i, shifted);
    EXPECT_NEAR(o.offset_px.x(), 1.0, 0.5) << "pair " << i;
    EXPECT_DOUBLE_EQ(o.loss_px, 0.0) << "pair " << i;
    mean_x += o.offset_px.x() / static_cast<double>(p.size());
  }
  EXPECT_NEAR(mean_x, 1.0, 0.2);
}

TEST(ImageOffset, SameAnswerWhateverTheThreadCount) {
  const std::vector<CalibrationPair> p = pairs(3, 5);
  const LossEvaluator bilinear = bilinearOn(p);
  const Extrinsic shifted =
      offsetInImage(fieldsafeTruth(), fieldsafeCamera(), Eigen::Vector2d(0.7, 0.4));
  for (std::size_t i = 0; i < p.size(); ++i) {
    const ImageOffset one = pairImageOffset(bilinear, i, shifted, {}, 1);
    const ImageOffset two = pairImageOffset(bilinear, i, shifted, {}, 2);
    EXPECT_EQ(one.offset_px, two.offset_px);
    EXPECT_EQ(one.loss_px, two.loss_px);
  }
}

TEST(ImageOffset, RefusesABadGrid) {
  const std::vector<CalibrationPair> p = pairs(1, 6);
  const LossEvaluator bilinear = bilinearOn(p);
  ImageOffsetGrid grid;
  grid.step_px = 0.0;
  EXPECT_THROW(pairImageOffset(bilinear, 0, fieldsafeTruth(), grid), std::invalid_argument);
  grid = ImageOffsetGrid{};
  grid.range_px = 0.1;  // below one step
  EXPECT_THROW(pairImageOffset(bilinear, 0, fieldsafeTruth(), grid), std::invalid_argument);
}
