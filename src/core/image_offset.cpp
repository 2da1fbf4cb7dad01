#include "thermal_lidar_calibration/core/image_offset.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace thermal_lidar_calibration {

void ImageOffsetGrid::validate() const {
  if (!(step_px > 0.0 && std::isfinite(range_px) && range_px >= step_px &&
        range_px / step_px <= 1000.0 && tolerance_px >= 0.0 && std::isfinite(tolerance_px))) {
    throw std::invalid_argument(
        "image offset grid: need 0 < step_px <= range_px <= 1000 step_px and tolerance_px >= 0");
  }
}

Extrinsic offsetInImage(const Extrinsic& extrinsic, const CameraModel& camera,
                        const Eigen::Vector2d& offset_px) {
  // A turn about the camera's y axis by a moves a point near the optical axis by fx * a to the
  // right; one about its x axis by b moves it by fy * b up.
  const Eigen::Matrix3d turn =
      rodriguesToMatrix(Eigen::Vector3d(-offset_px.y() / camera.fy, offset_px.x() / camera.fx, 0.0));
  return Extrinsic::fromRotationMatrix(turn * extrinsic.rotationMatrix(),
                                       turn * extrinsic.translation);
}

ImageOffset pairImageOffset(const LossEvaluator& bilinear, std::size_t pair,
                            const Extrinsic& extrinsic, const ImageOffsetGrid& grid, int threads) {
  grid.validate();
  const int half = static_cast<int>(std::floor(grid.range_px / grid.step_px + 1e-9));
  std::vector<Extrinsic> candidates;
  std::vector<Eigen::Vector2d> offsets;
  for (int iy = -half; iy <= half; ++iy) {
    for (int ix = -half; ix <= half; ++ix) {
      offsets.emplace_back(ix * grid.step_px, iy * grid.step_px);
      candidates.push_back(offsetInImage(extrinsic, bilinear.camera(), offsets.back()));
    }
  }
  std::vector<double> losses;
  bilinear.lossBatch(candidates, {pair}, losses, threads);
  const double lowest = *std::min_element(losses.begin(), losses.end());
  ImageOffset out;
  out.loss_px = lowest;
  std::size_t within = 0;
  for (std::size_t c = 0; c < losses.size(); ++c) {
    if (losses[c] <= lowest + grid.tolerance_px) {
      out.offset_px += offsets[c];
      ++within;
    }
  }
  out.offset_px /= static_cast<double>(within);
  return out;
}

}  // namespace thermal_lidar_calibration
