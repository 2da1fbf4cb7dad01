#include "thermal_lidar_calibration/synthetic/image_region.hpp"

#include <stdexcept>

namespace thermal_lidar_calibration {
namespace synthetic {

ImageRegion imageRegionByName(const std::string& name) {
  if (name == "left") return ImageRegion::kLeft;
  if (name == "centre") return ImageRegion::kCentre;
  if (name == "right") return ImageRegion::kRight;
  if (name == "none") return ImageRegion::kNone;
  throw std::invalid_argument("unknown image region '" + name + "' (use left, centre or right)");
}

const char* toString(ImageRegion region) {
  switch (region) {
    case ImageRegion::kLeft: return "left";
    case ImageRegion::kCentre: return "centre";
    case ImageRegion::kRight: return "right";
    case ImageRegion::kNone: break;
  }
  return "none";
}

ColumnRange regionColumns(ImageRegion region, int width) {
  if (region == ImageRegion::kNone || width <= 0) return {};
  const int k = region == ImageRegion::kLeft ? 0 : (region == ImageRegion::kCentre ? 1 : 2);
  // Smallest u with u * 3 / width >= k is ceil(k * width / 3).
  return {(k * width + 2) / 3, ((k + 1) * width + 2) / 3};
}

}  // namespace synthetic
}  // namespace thermal_lidar_calibration
