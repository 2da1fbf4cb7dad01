#include "thermal_lidar_calibration/detection/image_flip.hpp"

#include <stdexcept>

namespace thermal_lidar_calibration {
namespace detection {

ImageFlip parseImageFlip(const std::string& text) {
  if (text == "none") return ImageFlip::kNone;
  if (text == "vertical") return ImageFlip::kVertical;
  if (text == "horizontal") return ImageFlip::kHorizontal;
  if (text == "both") return ImageFlip::kBoth;
  throw std::invalid_argument("image flip '" + text +
                              "': must be one of {none, vertical, horizontal, both}");
}

const char* toString(ImageFlip flip) {
  switch (flip) {
    case ImageFlip::kVertical: return "vertical";
    case ImageFlip::kHorizontal: return "horizontal";
    case ImageFlip::kBoth: return "both";
    case ImageFlip::kNone: break;
  }
  return "none";
}

cv::Mat flipImage(const cv::Mat& image, ImageFlip flip) {
  if (flip == ImageFlip::kNone) return image;
  // cv::flip codes: 0 = about the x axis (upside down), 1 = about the y axis (mirror), -1 = both.
  const int code = flip == ImageFlip::kVertical ? 0 : flip == ImageFlip::kHorizontal ? 1 : -1;
  cv::Mat out;
  cv::flip(image, out, code);
  return out;
}

}  // namespace detection
}  // namespace thermal_lidar_calibration
