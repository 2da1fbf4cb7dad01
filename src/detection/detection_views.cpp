#include "thermal_lidar_calibration/detection/detection_views.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace thermal_lidar_calibration {
namespace detection {
namespace {

cv::Scalar colourOf(int id) {
  static const cv::Scalar kPalette[] = {{0, 200, 255}, {255, 120, 0}, {0, 255, 0}, {255, 0, 255},
                                        {0, 128, 255}, {255, 255, 0}, {128, 0, 255}, {0, 255, 160}};
  return kPalette[(id - 1) % 8];
}

// The image as 8-bit grey, stretched between its 1st and 99th percentiles.
cv::Mat stretchToGrey(const cv::Mat& image) {
  cv::Mat values;
  image.reshape(1, 1).convertTo(values, CV_32F);
  std::vector<float> v(values.begin<float>(), values.end<float>());
  const std::size_t lo_i = v.size() / 100, hi_i = v.size() - 1 - v.size() / 100;
  std::nth_element(v.begin(), v.begin() + lo_i, v.end());
  const float lo = v[lo_i];
  std::nth_element(v.begin(), v.begin() + hi_i, v.end());
  const float hi = std::max(v[hi_i], lo + 1.f);
  cv::Mat grey;
  image.convertTo(grey, CV_8U, 255.0 / (hi - lo), -lo * 255.0 / (hi - lo));
  return grey;
}

}  // namespace

cv::Mat renderMaskOverlay(const cv::Mat& image, const ThermalSegmentation& segmentation) {
  cv::Mat view;
  cv::cvtColor(stretchToGrey(image), view, cv::COLOR_GRAY2BGR);
  for (const auto& person : segmentation.people) {
    const cv::Scalar colour = colourOf(person.id);
    cv::Mat tint(view.size(), view.type(), colour);
    cv::Mat blended;
    cv::addWeighted(view, 0.5, tint, 0.5, 0, blended);
    blended.copyTo(view, segmentation.mask == person.id);
    cv::rectangle(view, person.bbox, colour, 1);
    cv::putText(view, std::to_string(person.id), person.bbox.tl() + cv::Point(0, -3), cv::FONT_HERSHEY_SIMPLEX, 0.45,
                colour, 1);
  }
  return view;
}

cv::Mat renderBirdsEye(const std::vector<Eigen::Vector3f>& points, const LidarDetection& detection,
                       const LidarPersonDetector& detector, double range_m, double px_per_m) {
  const int side = static_cast<int>(std::ceil(2 * range_m * px_per_m));
  cv::Mat view(side, side, CV_8UC3, cv::Scalar(0, 0, 0));
  const auto& levelled = detector.ground().levelledPoints();
  const auto& heights = detector.ground().heights();
  auto pixel = [&](const Eigen::Vector3f& p) {
    return cv::Point(static_cast<int>(side / 2 - p.y() * px_per_m), static_cast<int>(side / 2 - p.x() * px_per_m));
  };
  for (int r = 5; r <= range_m; r += 5) {
    cv::circle(view, cv::Point(side / 2, side / 2), static_cast<int>(r * px_per_m), cv::Scalar(40, 40, 40), 1);
  }
  for (std::size_t i = 0; i < points.size() && i < levelled.size(); ++i) {
    if (!std::isfinite(heights[i])) continue;
    const cv::Point q = pixel(levelled[i]);
    if (q.x < 0 || q.y < 0 || q.x >= side || q.y >= side) continue;
    const int g = static_cast<int>(std::clamp(60.f + heights[i] * 90.f, 40.f, 255.f));
    view.at<cv::Vec3b>(q) = cv::Vec3b(static_cast<std::uint8_t>(g), static_cast<std::uint8_t>(g), static_cast<std::uint8_t>(g));
  }
  for (const auto& object : detection.rejected) {
    if (object.shape.top_m < 1.0f || object.indices.size() < 3) continue;
    std::vector<cv::Point> pts;
    for (int i : object.indices) pts.push_back(pixel(levelled[i]));
    cv::rectangle(view, cv::boundingRect(pts), cv::Scalar(0, 0, 140), 1);
  }
  for (std::size_t j = 0; j < detection.indices.size(); ++j) {
    const cv::Point q = pixel(levelled[detection.indices[j]]);
    cv::circle(view, q, 1, colourOf(static_cast<int>(detection.labels[j])), cv::FILLED);
  }
  for (const auto& person : detection.people) {
    const Eigen::Vector3f c = detector.ground().levelFromSensor() * person.centroid;
    cv::putText(view, std::to_string(person.label), pixel(c) + cv::Point(6, -6), cv::FONT_HERSHEY_SIMPLEX, 0.5,
                colourOf(static_cast<int>(person.label)), 1);
  }
  return view;
}

}  // namespace detection
}  // namespace thermal_lidar_calibration
