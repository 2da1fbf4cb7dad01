#pragma once
// A third of the image width (issue #8's coverage case: people never walked there). Column u is
// in third k when u * 3 / width == k.

#include <cstdint>
#include <string>

namespace thermal_lidar_calibration {
namespace synthetic {

enum class ImageRegion : std::uint8_t { kNone, kLeft, kCentre, kRight };

// "left" | "centre" | "right" | "none"; anything else throws std::invalid_argument.
ImageRegion imageRegionByName(const std::string& name);
const char* toString(ImageRegion region);  // "left", "centre", "right", "none"

// Columns [begin, end) of the region in an image `width` pixels wide (empty for kNone).
struct ColumnRange {
  int begin = 0;
  int end = 0;
  bool contains(int u) const { return u >= begin && u < end; }
};
ColumnRange regionColumns(ImageRegion region, int width);

}  // namespace synthetic
}  // namespace thermal_lidar_calibration
