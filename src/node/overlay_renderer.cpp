// Overlay drawing: thermal image, mask outline, projected person points and range-coloured cloud.

#include "thermal_lidar_calibration/node/overlay_renderer.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <array>
#include <cmath>

namespace thermal_lidar_calibration {
namespace {

const std::array<cv::Scalar, 8> kLabelColours = {
    cv::Scalar(0, 255, 0),   cv::Scalar(255, 0, 255), cv::Scalar(0, 255, 255),
    cv::Scalar(255, 128, 0), cv::Scalar(0, 128, 255), cv::Scalar(255, 255, 0),
    cv::Scalar(128, 0, 255), cv::Scalar(0, 0, 255)};

cv::Mat toBgr(const cv::Mat& thermal) {
  cv::Mat gray8;
  if (thermal.depth() == CV_8U) {
    gray8 = thermal;
  } else {
    double lo = 0.0, hi = 0.0;
    cv::minMaxLoc(thermal, &lo, &hi);
    const double scale = hi > lo ? 255.0 / (hi - lo) : 1.0;
    thermal.convertTo(gray8, CV_8U, scale, -lo * scale);
  }
  cv::Mat bgr;
  cv::cvtColor(gray8, bgr, cv::COLOR_GRAY2BGR);
  return bgr;
}

}  // namespace

OverlayRenderer::OverlayRenderer(CameraModel camera, int max_points, double max_range_m)
    : camera_(std::move(camera)), max_points_(std::max(1, max_points)), max_range_m_(max_range_m) {
  cv::Mat ramp(256, 1, CV_8UC1);
  for (int i = 0; i < 256; ++i) ramp.at<std::uint8_t>(i) = static_cast<std::uint8_t>(i);
  cv::applyColorMap(ramp, range_lut_, cv::COLORMAP_JET);
}

cv::Mat OverlayRenderer::render(const OverlayInput& input) const {
  cv::Mat out = toBgr(input.thermal);
  if (!input.mask.empty() && input.mask.size() == out.size()) {
    cv::Mat binary = input.mask != 0;
    std::vector<std::vector<cv::Point>> contours;
    cv::findContours(binary, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE);
    cv::drawContours(out, contours, -1, cv::Scalar(255, 255, 255), 1);
  }
  if (input.estimate == nullptr) return out;

  const Eigen::Matrix3d R = input.estimate->rotationMatrix();
  const Eigen::Vector3d t = input.estimate->translation;
  const auto project = [&](const Eigen::Vector3f& p_lidar, cv::Point& pixel) {
    const Eigen::Vector3d p_camera = R * p_lidar.cast<double>() + t;
    if (p_camera.z() <= 0.05) return false;
    const Eigen::Vector2d uv = camera_.project(p_camera);
    if (!(uv.x() >= 0 && uv.y() >= 0 && uv.x() < out.cols && uv.y() < out.rows)) return false;
    pixel = cv::Point(static_cast<int>(std::lround(uv.x())), static_cast<int>(std::lround(uv.y())));
    return true;
  };

  const std::size_t n_cloud = input.cloud_points ? input.cloud_points->size() : 0;
  const std::size_t stride =
      std::max<std::size_t>(1, (n_cloud + max_points_ - 1) / static_cast<std::size_t>(max_points_));
  cv::Point pixel;
  for (std::size_t i = 0; i < n_cloud; i += stride) {
    const Eigen::Vector3f& p = (*input.cloud_points)[i];
    if (!project(p, pixel)) continue;
    const double range = p.norm();
    const int bin = std::clamp(static_cast<int>(255.0 * range / max_range_m_), 0, 255);
    const cv::Vec3b c = range_lut_.at<cv::Vec3b>(bin);
    cv::circle(out, pixel, 1, cv::Scalar(c[0], c[1], c[2]), cv::FILLED);
  }
  for (std::size_t i = 0; i < input.cluster_points.size(); ++i) {
    if (!project(input.cluster_points[i], pixel)) continue;
    const std::int32_t label = i < input.cluster_labels.size() ? input.cluster_labels[i] : 0;
    const cv::Scalar& colour =
        kLabelColours[static_cast<std::size_t>(std::abs(label)) % kLabelColours.size()];
    cv::circle(out, pixel, 2, colour, cv::FILLED);
  }
  return out;
}

}  // namespace thermal_lidar_calibration
