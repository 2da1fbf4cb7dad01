#include "thermal_lidar_calibration/core/distance_map.hpp"

#include "float_ops.hpp"

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace thermal_lidar_calibration {

DistanceMap::DistanceMap(const cv::Mat& mask) {
  if (mask.empty() || mask.type() != CV_8UC1) {
    throw std::invalid_argument("distance map: needs a non-empty CV_8UC1 binary mask");
  }
  const cv::Rect people = cv::boundingRect(mask);  // box of the non-zero pixels
  if (people.empty()) {
    throw std::invalid_argument("distance map: the person mask has no person pixel");
  }
  const int min_x = people.x, min_y = people.y;
  int max_x = people.x + people.width - 1, max_y = people.y + people.height - 1;
  // The bilinear rule reads a 2x2 neighbourhood, so the box is at least 2x2. Any box that holds
  // every person pixel gives exact distances, even one reaching past the image border.
  if (max_x == min_x) ++max_x;
  if (max_y == min_y) ++max_y;
  x0_ = min_x;
  y0_ = min_y;
  width_ = max_x - min_x + 1;
  height_ = max_y - min_y + 1;

  // Two-pass city-block transform: exact for the L1 metric with unit 4-neighbour steps.
  const float inf = std::numeric_limits<float>::max() / 4;
  values_.assign(static_cast<std::size_t>(width_) * height_, inf);
  for (int y = 0; y < height_; ++y) {
    const int v = y0_ + y;
    if (v >= mask.rows) continue;
    const std::uint8_t* row = mask.ptr<std::uint8_t>(v);
    for (int x = 0; x < width_; ++x) {
      const int u = x0_ + x;
      if (u < mask.cols && row[u]) values_[static_cast<std::size_t>(y) * width_ + x] = 0.0f;
    }
  }
  for (int y = 0; y < height_; ++y) {
    float* r = &values_[static_cast<std::size_t>(y) * width_];
    const float* up = y > 0 ? r - width_ : nullptr;
    for (int x = 0; x < width_; ++x) {
      if (up) r[x] = std::min(r[x], up[x] + 1.0f);
      if (x > 0) r[x] = std::min(r[x], r[x - 1] + 1.0f);
    }
  }
  for (int y = height_ - 1; y >= 0; --y) {
    float* r = &values_[static_cast<std::size_t>(y) * width_];
    const float* down = y + 1 < height_ ? r + width_ : nullptr;
    for (int x = width_ - 1; x >= 0; --x) {
      if (down) r[x] = std::min(r[x], down[x] + 1.0f);
      if (x + 1 < width_) r[x] = std::min(r[x], r[x + 1] + 1.0f);
    }
  }
}

float DistanceMap::atPixel(int u, int v) const {
  const int cu = std::clamp(u, x0_, x0_ + width_ - 1);
  const int cv = std::clamp(v, y0_, y0_ + height_ - 1);
  return static_cast<float>(std::abs(u - cu) + std::abs(v - cv)) +
         values_[static_cast<std::size_t>(cv - y0_) * width_ + (cu - x0_)];
}

float DistanceMap::nearest(float u, float v) const {
  // Pixel rule of the paper: the projected point takes the nearest pixel centre; ties (.5) go up.
  const float ru = std::floor(u + 0.5f), rv = std::floor(v + 0.5f);
  const float cu = clampps(ru, static_cast<float>(x0_), static_cast<float>(x0_ + width_ - 1));
  const float cv = clampps(rv, static_cast<float>(y0_), static_cast<float>(y0_ + height_ - 1));
  const int ix = static_cast<int>(cu) - x0_;
  const int iy = static_cast<int>(cv) - y0_;
  return minps(std::fabs(ru - cu) + std::fabs(rv - cv), kOffBoxCap) +
         values_[static_cast<std::size_t>(iy) * width_ + ix];
}

float DistanceMap::bilinear(float u, float v) const {
  const float cu = clampps(u, static_cast<float>(x0_), static_cast<float>(x0_ + width_ - 1));
  const float cv = clampps(v, static_cast<float>(y0_), static_cast<float>(y0_ + height_ - 1));
  const float fx = cu - static_cast<float>(x0_);
  const float fy = cv - static_cast<float>(y0_);
  const int ix = std::min(static_cast<int>(fx), width_ - 2);
  const int iy = std::min(static_cast<int>(fy), height_ - 2);
  const float ax = fx - static_cast<float>(ix);
  const float ay = fy - static_cast<float>(iy);
  const float* p = &values_[static_cast<std::size_t>(iy) * width_ + ix];
  const float top = p[0] + ax * (p[1] - p[0]);
  const float bottom = p[width_] + ax * (p[width_ + 1] - p[width_]);
  return minps(std::fabs(u - cu) + std::fabs(v - cv), kOffBoxCap) + (top + ay * (bottom - top));
}

std::shared_ptr<const DistanceMap> sharedDistanceMap(const cv::Mat& mask) {
  try {
    return std::make_shared<const DistanceMap>(mask);
  } catch (const std::invalid_argument&) {
    return nullptr;
  }
}

}  // namespace thermal_lidar_calibration
