#include "thermal_lidar_calibration/synthetic/thermal_renderer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace thermal_lidar_calibration {
namespace synthetic {
namespace {

constexpr double kNearZ = 0.05;       // m: objects closer to the camera plane are cast everywhere
constexpr int kBoxMarginPx = 3;       // margin around projected boxes (distortion, rounding)
constexpr double kSpeckleFraction = 0.002;  // share of pixels with temporal noise

}  // namespace

ThermalRenderer::ThermalRenderer(const CameraModel& camera, const Extrinsic& T_camera_lidar, double ground_z)
    : camera_(camera) {
  camera_.validate();
  const Eigen::Matrix3d R = T_camera_lidar.rotationMatrix();
  R_lidar_camera_ = R.transpose();
  camera_origin_lidar_ = -R_lidar_camera_ * T_camera_lidar.translation;

  const int w = camera_.width, h = camera_.height;
  rays_lidar_.resize(static_cast<std::size_t>(w) * h);
  background_.create(h, w, CV_32FC1);
  const double cam_height = camera_origin_lidar_.z() - ground_z;
  for (int v = 0; v < h; ++v) {
    for (int u = 0; u < w; ++u) {
      const Eigen::Vector3d ray_c = pixelRayCamera(u, v);
      const Eigen::Vector2d back = camera_.project(ray_c);
      max_round_trip_px_ = std::max(max_round_trip_px_, (back - Eigen::Vector2d(u, v)).norm());
      const Eigen::Vector3d d = R_lidar_camera_ * ray_c;
      rays_lidar_[static_cast<std::size_t>(v) * w + u] = d.cast<float>();
      // Background: cool sky above the horizon, ground warming towards the vehicle.
      float grey = 38.f;
      if (d.z() < -1e-3) {
        const double dist = cam_height / -d.z();
        grey = static_cast<float>(70.0 + 30.0 * std::exp(-dist / 25.0));
      } else {
        grey = static_cast<float>(60.0 - 25.0 * std::min(1.0, d.z() * 4.0));
      }
      background_.at<float>(v, u) = grey;
    }
  }
}

Eigen::Vector3d ThermalRenderer::pixelRayCamera(double u, double v) const {
  const double yd = (v - camera_.cy) / camera_.fy;
  const double xd = (u - camera_.cx - camera_.skew * yd) / camera_.fx;
  const Eigen::Vector2d target(xd, yd);
  Eigen::Vector2d x = target;
  if (camera_.hasDistortion()) {
    // Newton iterations on distort(x) = target with a numerical Jacobian.
    for (int it = 0; it < 20; ++it) {
      const Eigen::Vector2d f = camera_.distort(x) - target;
      if (f.norm() < 1e-12) break;
      constexpr double kH = 1e-7;
      Eigen::Matrix2d J;
      J.col(0) = (camera_.distort(x + Eigen::Vector2d(kH, 0)) - camera_.distort(x)) / kH;
      J.col(1) = (camera_.distort(x + Eigen::Vector2d(0, kH)) - camera_.distort(x)) / kH;
      x -= J.inverse() * f;
    }
  }
  return Eigen::Vector3d(x.x(), x.y(), 1.0).normalized();
}

cv::Mat ThermalRenderer::renderOwners(const std::vector<WorldObject>& objects) const {
  const int w = camera_.width, h = camera_.height;
  cv::Mat owners(h, w, CV_32SC1, cv::Scalar(-1));
  cv::Mat depth(h, w, CV_64FC1, cv::Scalar(std::numeric_limits<double>::infinity()));
  const Eigen::Matrix3d R_camera_lidar = R_lidar_camera_.transpose();
  Ray ray;
  ray.origin = camera_origin_lidar_;
  for (std::size_t j = 0; j < objects.size(); ++j) {
    const Solid& solid = objects[j].solid;
    // Pixel box of the object's axis-aligned box (projection of a convex hull).
    int u0 = 0, v0 = 0, u1 = w - 1, v1 = h - 1;
    bool all_front = true, any_front = false;
    double umin = 1e18, umax = -1e18, vmin = 1e18, vmax = -1e18;
    for (const auto& corner : solid.boundingBoxCorners()) {
      const Eigen::Vector3d pc = R_camera_lidar * (corner - camera_origin_lidar_);
      if (pc.z() < kNearZ) {
        all_front = false;
        continue;
      }
      any_front = true;
      const Eigen::Vector2d px = camera_.project(pc);
      umin = std::min(umin, px.x());
      umax = std::max(umax, px.x());
      vmin = std::min(vmin, px.y());
      vmax = std::max(vmax, px.y());
    }
    if (!any_front) continue;
    if (all_front) {
      if (umax < -kBoxMarginPx || vmax < -kBoxMarginPx || umin > w - 1 + kBoxMarginPx ||
          vmin > h - 1 + kBoxMarginPx) {
        continue;
      }
      u0 = std::max(0, static_cast<int>(std::floor(umin)) - kBoxMarginPx);
      v0 = std::max(0, static_cast<int>(std::floor(vmin)) - kBoxMarginPx);
      u1 = std::min(w - 1, static_cast<int>(std::ceil(umax)) + kBoxMarginPx);
      v1 = std::min(h - 1, static_cast<int>(std::ceil(vmax)) + kBoxMarginPx);
    }
    for (int v = v0; v <= v1; ++v) {
      int* own = owners.ptr<int>(v);
      double* dep = depth.ptr<double>(v);
      for (int u = u0; u <= u1; ++u) {
        ray.direction = rays_lidar_[static_cast<std::size_t>(v) * w + u].cast<double>();
        double t = 0.0;
        if (solid.intersect(ray, dep[u], &t)) {
          dep[u] = t;
          own[u] = static_cast<int>(j);
        }
      }
    }
  }
  return owners;
}

namespace {

// std::lround, without its library call when x is already whole (every grey level is: the scene
// and the noise are rounded before they are summed); half of a bag's rendering went to lround.
long roundToLong(double x) {
  if (!(std::fabs(x) < 1e15)) return std::lround(x);
  const long whole = static_cast<long>(x);
  return static_cast<double>(whole) == x ? whole : std::lround(x);
}

}  // namespace

cv::Mat ThermalRenderer::renderImage(const cv::Mat& owners, const std::vector<WorldObject>& objects,
                                     ImageDepth image_depth, double noise_level, double background_offset,
                                     std::mt19937_64& rng) const {
  const int w = camera_.width, h = camera_.height;
  // Column fixed-pattern noise (as uncooled microbolometers show) plus a few speckles: looks
  // noisy, but rows still repeat byte for byte, so LZ4 keeps the bag small.
  std::normal_distribution<float> gauss(0.f, 1.f);
  std::vector<float> column_noise(static_cast<std::size_t>(w));
  for (auto& n : column_noise) n = static_cast<float>(noise_level) * gauss(rng);
  // Each column's noise rounded once, not once per pixel (the same values).
  std::vector<float> column_grey(column_noise.size());
  for (std::size_t u = 0; u < column_noise.size(); ++u) column_grey[u] = std::round(column_noise[u]);
  cv::Mat speckle(h, w, CV_32FC1, cv::Scalar(0));
  std::uniform_int_distribution<int> pick_u(0, w - 1), pick_v(0, h - 1);
  const int speckles = static_cast<int>(kSpeckleFraction * w * h);
  for (int i = 0; i < speckles; ++i) {
    const int u = pick_u(rng), v = pick_v(rng);
    speckle.at<float>(v, u) = std::round(static_cast<float>(2.0 * noise_level)) * (gauss(rng) > 0.f ? 1.f : -1.f);
  }

  cv::Mat out(h, w, image_depth == ImageDepth::kMono8 ? CV_8UC1 : CV_16UC1);
  for (int v = 0; v < h; ++v) {
    const int* own = owners.ptr<int>(v);
    const float* bg = background_.ptr<float>(v);
    for (int u = 0; u < w; ++u) {
      // Quantise the scene first, then add integer noise: equal rows stay equal.
      double grey = std::round(bg[u] + background_offset);
      if (own[u] >= 0) {
        const WorldObject& obj = objects[static_cast<std::size_t>(own[u])];
        grey = std::round(obj.grey_level - (obj.isPerson() ? 10.0 * v / h : 0.0));  // warmer head
      }
      grey += column_grey[static_cast<std::size_t>(u)] + speckle.at<float>(v, u);
      if (image_depth == ImageDepth::kMono8) {
        out.at<std::uint8_t>(v, u) = static_cast<std::uint8_t>(std::clamp(roundToLong(grey), 0L, 255L));
      } else if (image_depth == ImageDepth::kMono16Radiometric) {
        const double kelvin = kRawKelvinAtGreyZero + kRawKelvinPerGrey * grey;
        out.at<std::uint16_t>(v, u) =
            static_cast<std::uint16_t>(std::clamp(std::lround(kelvin / kRawKelvinPerCount), 0L, 65535L));
      } else {
        out.at<std::uint16_t>(v, u) =
            static_cast<std::uint16_t>(std::clamp(roundToLong(7000.0 + 16.0 * grey), 0L, 65535L));
      }
    }
  }
  return out;
}

}  // namespace synthetic
}  // namespace thermal_lidar_calibration
