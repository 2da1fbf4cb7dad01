#pragma once
// The thermal camera: per-pixel ray casting through the lens model (each pixel centre is
// undistorted to a ray once, at construction), so occlusion in the mask is exact. Only pixels in
// the projected bounding box of each object are cast.

#include "thermal_lidar_calibration/core/camera_model.hpp"
#include "thermal_lidar_calibration/core/extrinsic.hpp"
#include "thermal_lidar_calibration/synthetic/world_object.hpp"

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include <cstdint>
#include <random>
#include <vector>

namespace thermal_lidar_calibration {
namespace synthetic {

// kMono16Radiometric: counts = kelvin / kRawKelvinPerCount (FLIR Ax5 high-resolution linear
// mode), kelvin = kRawKelvinAtGreyZero + kRawKelvinPerGrey * grey: background 276-283 K, sky
// ~270 K, people (grey 185-215) 300-307 K.
enum class ImageDepth : std::uint8_t { kMono8, kMono16, kMono16Radiometric };
constexpr double kRawKelvinPerCount = 0.04;
constexpr double kRawKelvinAtGreyZero = 262.0;
constexpr double kRawKelvinPerGrey = 0.21;

class ThermalRenderer {
 public:
  // `T_camera_lidar` is the true extrinsic; `ground_z` the ground height in the LiDAR frame.
  ThermalRenderer(const CameraModel& camera, const Extrinsic& T_camera_lidar, double ground_z);

  // Inverse of CameraModel::project for a pixel (u right, v down): unit ray in the camera frame.
  Eigen::Vector3d pixelRayCamera(double u, double v) const;
  // Largest |project(ray(u, v)) - (u, v)| over the pixel centres, px (a self-check).
  double maxRoundTripErrorPx() const { return max_round_trip_px_; }

  // For every pixel, the index of the nearest object hit (CV_32SC1, -1 = none/ground).
  cv::Mat renderOwners(const std::vector<WorldObject>& objects) const;
  // Thermal image from the owner map: smooth sky/ground background, objects at their grey
  // level, a little column pattern noise and speckle (compressible). CV_8UC1 or CV_16UC1 (7000 + 16 * grey).
  cv::Mat renderImage(const cv::Mat& owners, const std::vector<WorldObject>& objects, ImageDepth depth,
                      double noise_level, double background_offset, std::mt19937_64& rng) const;

  const CameraModel& camera() const { return camera_; }

 private:
  CameraModel camera_;
  Eigen::Matrix3d R_lidar_camera_;
  Eigen::Vector3d camera_origin_lidar_;
  std::vector<Eigen::Vector3f> rays_lidar_;  // per pixel, row-major, unit, LiDAR frame
  cv::Mat background_;                       // CV_32FC1 grey levels
  double max_round_trip_px_ = 0.0;
};

}  // namespace synthetic
}  // namespace thermal_lidar_calibration
