#pragma once
// Exact L1 (Manhattan) distance from every pixel to the nearest person pixel (psi of Eq. 2).
//
// Only the bounding box of the person pixels is stored: for any point p and any box B that
// contains every person pixel, min_q |p - q|_1 = |p - clamp_B(p)|_1 + DT(clamp_B(p)), because on
// each axis the clamped coordinate lies between p and every q. So the crop gives the same
// numbers as a full-image map, for points inside the image, outside it, or far away, while
// using ~15x less memory (it stays in cache during the sweep over candidates).

#include <opencv2/core.hpp>

#include <memory>
#include <vector>

namespace thermal_lidar_calibration {

class DistanceMap {
 public:
  // binary_mask: CV_8UC1, non-zero = person. Throws std::invalid_argument without person pixels.
  explicit DistanceMap(const cv::Mat& binary_mask);

  // Crop box in image pixels: columns [x0, x0 + width), rows [y0, y0 + height).
  int x0() const { return x0_; }
  int y0() const { return y0_; }
  int width() const { return width_; }
  int height() const { return height_; }
  const float* data() const { return values_.data(); }  // row-major, width() x height()

  // |p - clamp_B(p)|_1 is capped here: a projection with z -> 0+ can be infinite (or NaN, which
  // clamps to the box corner and costs the cap), and 2e6 px already costs far more than the
  // behind-camera penalty at its default. The loss kernels use the same cap.
  static constexpr float kOffBoxCap = 2e6f;

  // Exact integer L1 distance for pixel (u, v) anywhere (inside the image or not).
  float atPixel(int u, int v) const;
  // "nearest" pixel rule (the paper's): round (u, v) to the nearest pixel centre, then exact L1.
  float nearest(float u, float v) const;
  // "bilinear" rule: |p - clamp_B(p)|_1 + bilinear interpolation of the map at clamp_B(p).
  // Continuous in p, equal to the exact distance at pixel centres.
  float bilinear(float u, float v) const;

 private:
  int x0_ = 0, y0_ = 0, width_ = 0, height_ = 0;
  std::vector<float> values_;
};

// The map of `mask` for a caller that builds it once for every evaluator of its pair
// (CalibrationPair::distance_map); null for a mask it cannot be built from, which is then left to
// the evaluator to report (it says which pair and what is wrong).
std::shared_ptr<const DistanceMap> sharedDistanceMap(const cv::Mat& mask);

}  // namespace thermal_lidar_calibration
