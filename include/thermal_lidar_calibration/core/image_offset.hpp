#pragma once
// Where a pair's people sit in the image against an extrinsic: the drift watch's low-noise
// statistic (drift_window_comparison.hpp).
//
// The offset is a pan/tilt of the camera about its own centre, in image pixels (x right, y
// down), that best aligns the pair's LiDAR points with its mask under Eq. (1). Eq. (1) is the
// distance to the nearest mask pixel, zero inside the mask, so with masks a pixel or two wider
// or narrower than the person (segmentation noise) it is flat over a range of offsets; a search
// started at the extrinsic stops at the near end of that range, which is why a small change
// hardly moves a window's fit. The middle of the range moves with the change, though: the
// offset here is the mean of the grid offsets whose loss is within `tolerance_px` of the
// lowest. Measured on 20-minute synthetic drives with realistic noise (mask edges +-2 px): with
// the true extrinsic a pair's offset scatters ~0.3 px across the image (people are upright,
// their left and right edges sharp) but ~2-2.5 px down it (the LiDAR's rings sample a person's
// height 1.3 deg apart, ~18 px in the FieldSAFE-like image).

#include "thermal_lidar_calibration/core/camera_model.hpp"
#include "thermal_lidar_calibration/core/extrinsic.hpp"
#include "thermal_lidar_calibration/core/loss.hpp"

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace thermal_lidar_calibration {

// The search grid: square, +-range_px in x and y at step_px, and the loss tolerance that makes
// a grid point part of the lowest range. Measured on the 20-minute stable drives: a 0.5 px step
// let the significant windows' offsets across reach 0.30 px (0.25 px: 0.25), a 0.05 px
// tolerance raised changes there (0.01 and 0.02 none); +-8 px clipped the rows of a 0.5 deg
// turn (3.4 px down against 4.1 px with +-12, 5.2 px true).
struct ImageOffsetGrid {
  double range_px = 12.0;
  double step_px = 0.25;
  double tolerance_px = 0.01;
  void validate() const;  // throws std::invalid_argument
};

struct ImageOffset {
  Eigen::Vector2d offset_px = Eigen::Vector2d::Zero();  // image x (right), y (down)
  double loss_px = 0.0;  // Eq. (1), bilinear, at the best grid offset
};

// `extrinsic` turned about the camera centre so that points near the image centre move by
// offset_px (a rotation of offset_px.x() / fx about the camera's y axis and -offset_px.y() / fy
// about its x axis).
Extrinsic offsetInImage(const Extrinsic& extrinsic, const CameraModel& camera,
                        const Eigen::Vector2d& offset_px);

// Pair `pair` of `bilinear` (an evaluator with PixelRule::kBilinear) against `extrinsic`.
// Deterministic whatever `threads` (0 = all cores).
ImageOffset pairImageOffset(const LossEvaluator& bilinear, std::size_t pair,
                            const Extrinsic& extrinsic, const ImageOffsetGrid& grid = {},
                            int threads = 1);

}  // namespace thermal_lidar_calibration
