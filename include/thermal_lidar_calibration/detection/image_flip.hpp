#pragma once
// Input flip for cameras that store their images mirrored or upside down (FieldSAFE's FLIR A65
// images are reportedly stored upside down: its own viewer flips them vertically). A mirrored
// image has no rigid extrinsic, so the flip must happen before segmentation and calibration.

#include <opencv2/core.hpp>

#include <string>

namespace thermal_lidar_calibration {
namespace detection {

enum class ImageFlip { kNone, kVertical, kHorizontal, kBoth };

// "none" | "vertical" | "horizontal" | "both"; throws std::invalid_argument otherwise.
ImageFlip parseImageFlip(const std::string& text);
const char* toString(ImageFlip flip);

// The flipped image (a new buffer; the input itself when flip is kNone).
cv::Mat flipImage(const cv::Mat& image, ImageFlip flip);

}  // namespace detection
}  // namespace thermal_lidar_calibration
