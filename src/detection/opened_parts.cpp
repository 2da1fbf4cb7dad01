#include "opened_parts.hpp"

#include <algorithm>
#include <cmath>

namespace thermal_lidar_calibration {
namespace detection {
namespace {

template <typename T>
std::vector<double> coolestLevels(const cv::Mat& image, const cv::Mat& warm, const cv::Mat& ids,
                                  const std::vector<cv::Rect>& boxes, double quantile) {
  std::vector<double> floors(boxes.size(), 0.0);
  std::vector<T> levels;
  for (std::size_t k = 0; k < boxes.size(); ++k) {
    levels.clear();
    const cv::Rect& b = boxes[k];
    const auto id = static_cast<std::uint8_t>(k + 1);
    for (int y = b.y; y < b.y + b.height; ++y) {
      const std::uint8_t* row = ids.ptr<std::uint8_t>(y);
      const std::uint8_t* w = warm.ptr<std::uint8_t>(y);
      const T* pix = image.ptr<T>(y);
      for (int x = b.x; x < b.x + b.width; ++x) {
        // The closing's fill (the gap between the legs) is background, not the person.
        if (row[x] == id && w[x] != 0) levels.push_back(pix[x]);
      }
    }
    if (levels.empty()) continue;
    const auto nth = levels.begin() + static_cast<std::ptrdiff_t>(std::floor(quantile * (levels.size() - 1)));
    std::nth_element(levels.begin(), nth, levels.end());
    floors[k] = *nth;
  }
  return floors;
}

template <typename T>
void grow(const cv::Mat& image, const cv::Mat& warm, const cv::Mat& others, int steps, const std::vector<double>& floors,
          cv::Mat* ids, std::vector<cv::Rect>* boxes, std::vector<int>* areas) {
  const cv::Rect frame(0, 0, ids->cols, ids->rows);
  // Every step looks only around the people's boxes, grown by one pixel a step.
  cv::Rect area;
  for (const cv::Rect& b : *boxes) area |= b;
  // Every pixel of a step sees the regions as they were before it. Only the area changes, and it
  // only grows, so after the first copy a step copies just the area.
  cv::Mat before = ids->clone();
  for (int step = 0; step < steps; ++step) {
    area = cv::Rect(area.x - 1, area.y - 1, area.width + 2, area.height + 2) & frame;
    if (step > 0) (*ids)(area).copyTo(before(area));
    bool grew = false;
    for (int y = area.y; y < area.y + area.height; ++y) {
      const std::uint8_t* w = warm.ptr<std::uint8_t>(y);
      const std::uint8_t* other = others.empty() ? nullptr : others.ptr<std::uint8_t>(y);
      const T* pix = image.ptr<T>(y);
      const std::uint8_t* row = before.ptr<std::uint8_t>(y);
      const std::uint8_t* up = y > 0 ? before.ptr<std::uint8_t>(y - 1) : nullptr;
      const std::uint8_t* down = y + 1 < before.rows ? before.ptr<std::uint8_t>(y + 1) : nullptr;
      std::uint8_t* out = ids->ptr<std::uint8_t>(y);
      for (int x = area.x; x < area.x + area.width; ++x) {
        if (row[x] != 0 || w[x] == 0 || (other && other[x])) continue;
        int id = 256;
        if (x > 0 && row[x - 1]) id = std::min<int>(id, row[x - 1]);
        if (x + 1 < before.cols && row[x + 1]) id = std::min<int>(id, row[x + 1]);
        if (up && up[x]) id = std::min<int>(id, up[x]);
        if (down && down[x]) id = std::min<int>(id, down[x]);
        if (id == 256 || pix[x] < floors[static_cast<std::size_t>(id - 1)]) continue;
        out[x] = static_cast<std::uint8_t>(id);
        (*boxes)[static_cast<std::size_t>(id - 1)] |= cv::Rect(x, y, 1, 1);
        ++(*areas)[static_cast<std::size_t>(id - 1)];
        grew = true;
      }
    }
    if (!grew) return;  // nothing left to reach
  }
}

}  // namespace

void restoreOpenedParts(const cv::Mat& image, const cv::Mat& warm, const cv::Mat& regions, int steps, cv::Mat* ids,
                        std::vector<cv::Rect>* boxes, std::vector<int>* areas) {
  if (steps <= 0 || boxes->empty()) return;
  cv::Mat others;  // the regions that are not people: never grown into
  if (!regions.empty()) others = regions & (*ids == 0);
  if (image.depth() == CV_16U) {
    grow<std::uint16_t>(image, warm, others, steps, coolestLevels<std::uint16_t>(image, warm, *ids, *boxes, kCoolestQuantile), ids,
                        boxes, areas);
  } else {
    grow<std::uint8_t>(image, warm, others, steps, coolestLevels<std::uint8_t>(image, warm, *ids, *boxes, kCoolestQuantile), ids,
                       boxes, areas);
  }
}

}  // namespace detection
}  // namespace thermal_lidar_calibration
