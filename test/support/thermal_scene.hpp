#pragma once
// Crafted radiometric thermal images for the segmenter's tests and benchmark: 16-bit counts at
// kelvin = counts * 0.04 (the contract's default scale), a background at a given temperature with
// Gaussian noise from a fixed seed, and warm shapes drawn at known temperatures.

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

namespace thermal_lidar_calibration {
namespace test_support {

constexpr double kKelvinPerCount = 0.04;

inline double countsOf(double kelvin) { return kelvin / kKelvinPerCount; }

// A CV_16UC1 image at `kelvin` with per-pixel noise of sigma `noise_k` (Box-Muller, fixed seed).
inline cv::Mat thermalBackground(cv::Size size, double kelvin, double noise_k = 0.0, std::uint64_t seed = 1) {
  cv::Mat image(size, CV_16UC1, cv::Scalar(std::round(countsOf(kelvin))));
  if (noise_k <= 0) return image;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(1e-12, 1.0);
  for (int y = 0; y < image.rows; ++y) {
    auto* row = image.ptr<std::uint16_t>(y);
    for (int x = 0; x < image.cols; ++x) {
      const double g = std::sqrt(-2 * std::log(u(rng))) * std::cos(2 * M_PI * u(rng));
      row[x] = cv::saturate_cast<std::uint16_t>(row[x] + g * noise_k / kKelvinPerCount);
    }
  }
  return image;
}

inline void fillKelvin(cv::Mat& image, const cv::Rect& box, double kelvin) {
  cv::rectangle(image, box, cv::Scalar(std::round(countsOf(kelvin))), cv::FILLED);
}

// A standing person `height_px` tall with the top of the head at (cx, top): head disc, torso
// ellipse, two legs; the torso and legs at `clothing_k`, head (and hands) at `skin_k`.
inline void drawPerson(cv::Mat& image, int cx, int top, int height_px, double skin_k, double clothing_k) {
  const double h = height_px;
  const cv::Scalar skin(std::round(countsOf(skin_k))), cloth(std::round(countsOf(clothing_k)));
  const int head_r = static_cast<int>(std::round(0.065 * h));
  const cv::Point head(cx, top + head_r);
  const cv::Point torso(cx, top + static_cast<int>(0.33 * h));
  const cv::Size torso_axes(static_cast<int>(0.12 * h), static_cast<int>(0.2 * h));
  cv::ellipse(image, torso, torso_axes, 0, 0, 360, cloth, cv::FILLED);
  const int leg_w = std::max(2, static_cast<int>(0.06 * h));
  const int hip = top + static_cast<int>(0.48 * h);
  cv::rectangle(image, cv::Rect(cx - leg_w - 1, hip, leg_w, top + height_px - hip), cloth, cv::FILLED);
  cv::rectangle(image, cv::Rect(cx + 1, hip, leg_w, top + height_px - hip), cloth, cv::FILLED);
  cv::circle(image, head, head_r, skin, cv::FILLED);
  // Hands at the ends of the arms, beside the hips.
  const int hand = std::max(1, static_cast<int>(0.03 * h));
  cv::circle(image, cv::Point(cx - torso_axes.width - hand, hip), hand, skin, cv::FILLED);
  cv::circle(image, cv::Point(cx + torso_axes.width + hand, hip), hand, skin, cv::FILLED);
}

// A person `height_px` tall seen side on with the legs together (the body model's proportions:
// torso 0.24 m deep, legs 0.13 m, head 0.2 m of a 1.75 m adult): height / width ~7, as slender
// as a post, but the legs are about half as wide as the torso.
inline void drawPersonSideOn(cv::Mat& image, int cx, int top, int height_px, double skin_k, double clothing_k) {
  const double h = height_px;
  const cv::Scalar skin(std::round(countsOf(skin_k))), cloth(std::round(countsOf(clothing_k)));
  const int head_r = static_cast<int>(std::round(0.065 * h));
  cv::ellipse(image, cv::Point(cx, top + head_r), cv::Size(static_cast<int>(std::round(0.057 * h)), head_r), 0, 0,
              360, skin, cv::FILLED);
  const int hip = top + static_cast<int>(0.48 * h);
  cv::ellipse(image, cv::Point(cx, top + static_cast<int>(0.33 * h)),
              cv::Size(static_cast<int>(std::round(0.069 * h)), static_cast<int>(0.2 * h)), 0, 0, 360, cloth,
              cv::FILLED);
  const int leg_half = std::max(1, static_cast<int>(std::round(0.037 * h)));
  cv::rectangle(image, cv::Rect(cx - leg_half, hip, 2 * leg_half + 1, top + height_px - hip), cloth, cv::FILLED);
}

// A post `width_px` wide and `height_px` tall standing at (cx, bottom), leaning `tilt_deg` in the
// image (a vertical post seen by a rolled camera).
inline void drawPost(cv::Mat& image, int cx, int bottom, int width_px, int height_px, double tilt_deg,
                     double kelvin) {
  const double a = tilt_deg * M_PI / 180.0;
  const cv::Point2d up(std::sin(a), -std::cos(a)), across(std::cos(a), std::sin(a));
  const cv::Point2d base(cx, bottom);
  const double half = 0.5 * width_px;
  const cv::Point2d corners[4] = {base - half * across, base + half * across,
                                  base + half * across + height_px * up, base - half * across + height_px * up};
  std::vector<cv::Point> poly;
  for (const auto& c : corners) poly.emplace_back(static_cast<int>(std::lround(c.x)), static_cast<int>(std::lround(c.y)));
  cv::fillConvexPoly(image, poly, cv::Scalar(std::round(countsOf(kelvin))));
}

// A four-legged animal at body temperature: a horizontal body ellipse on short legs.
inline void drawAnimal(cv::Mat& image, int cx, int top, int length_px, double kelvin) {
  const cv::Scalar v(std::round(countsOf(kelvin)));
  const int body_h = length_px / 3;
  cv::ellipse(image, cv::Point(cx, top + body_h / 2), cv::Size(length_px / 2, body_h / 2), 0, 0, 360, v, cv::FILLED);
  const int leg = length_px / 4, leg_w = std::max(2, length_px / 14);
  for (int side : {-1, 1}) {
    cv::rectangle(image, cv::Rect(cx + side * length_px / 3 - leg_w / 2, top + body_h - 2, leg_w, leg), v, cv::FILLED);
  }
}

}  // namespace test_support
}  // namespace thermal_lidar_calibration
