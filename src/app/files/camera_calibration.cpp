#include "thermal_lidar_calibration/app/files/camera_calibration.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace thermal_lidar_calibration {

CameraModel cameraModelFromCalibration(const CameraCalibration& c) {
  constexpr long long kMaxSide = std::numeric_limits<int>::max();
  if (c.width <= 0 || c.height <= 0 || c.width > kMaxSide || c.height > kMaxSide) {
    throw std::invalid_argument("image size is " + std::to_string(c.width) + "x" +
                                std::to_string(c.height) +
                                "; give the calibrated width and height");
  }
  bool k_zero = true;
  for (double k : c.K) {
    if (!std::isfinite(k)) throw std::invalid_argument("K has a non-finite entry; give a calibrated K");
    if (k != 0.0) k_zero = false;
  }
  if (k_zero) {
    throw std::invalid_argument("K is all zeros (camera not calibrated); calibrate the "
                                "intrinsics or give a camera_calibration YAML file");
  }
  std::vector<double> D = c.D;
  for (double d : D) {
    if (!std::isfinite(d)) throw std::invalid_argument("D has a non-finite entry; give calibrated coefficients");
  }
  const bool all_zero = std::all_of(D.begin(), D.end(), [](double d) { return d == 0.0; });
  const std::string& model = c.distortion_model;
  if (model == "plumb_bob") {
    if (!D.empty() && D.size() != 5) {
      throw std::invalid_argument("plumb_bob needs 5 distortion coefficients (k1 k2 p1 p2 k3), got " +
                                  std::to_string(D.size()));
    }
  } else if (!all_zero) {
    throw std::invalid_argument(
        (model.empty() || model == "none")
            ? "distortion_model is '" + model + "' but D is non-zero; set distortion_model to plumb_bob"
            : "distortion_model '" + model +
                  "' is not supported; use plumb_bob (5 coefficients) or none, or rectify the "
                  "images first");
  }
  if (all_zero) D.clear();  // any model with all-zero coefficients is a plain pinhole
  CameraModel camera = CameraModel::fromK(static_cast<int>(c.width), static_cast<int>(c.height), c.K, D);
  camera.validate();
  return camera;
}

}  // namespace thermal_lidar_calibration
