#include "opened_parts.hpp"

#include <algorithm>

namespace thermal_lidar_calibration {
namespace detection {
namespace {

// Calls f(q) for each 4-neighbour q of p inside an image of `size`.
template <typename F>
void forEachNeighbour(const cv::Point& p, const cv::Size& size, F f) {
  const cv::Point around[4] = {{p.x - 1, p.y}, {p.x + 1, p.y}, {p.x, p.y - 1}, {p.x, p.y + 1}};
  for (const cv::Point& q : around) {
    if (q.x >= 0 && q.y >= 0 && q.x < size.width && q.y < size.height) f(q);
  }
}

// The background pixels 4-adjacent to `p` that are not in `seen`, appended to `out` and marked.
void addZeroNeighbours(const cv::Mat& ids, const cv::Point& p, cv::Mat* seen, std::vector<cv::Point>* out) {
  forEachNeighbour(p, ids.size(), [&](const cv::Point& q) {
    if (ids.at<std::uint8_t>(q) != 0 || seen->at<std::uint8_t>(q) != 0) return;
    seen->at<std::uint8_t>(q) = 1;
    out->push_back(q);
  });
}

// One step at a time, every background pixel next to a person as the people were before the step
// joins the lowest id among its 4-neighbours, if it is warm, not in another region and at least
// that person's floor. A pixel can only join in a step after one of its neighbours changed, so
// each step looks at the neighbours of the pixels the last one added (of every person pixel in
// the first): the cost follows the people's outline, not their boxes.
template <typename T>
void grow(const cv::Mat& image, const cv::Mat& warm, const cv::Mat& regions, int steps,
          const std::vector<double>& floors, cv::Mat* ids, std::vector<ThermalPerson>* people) {
  cv::Mat seen = cv::Mat::zeros(ids->size(), CV_8UC1);  // already a candidate this step
  std::vector<cv::Point> candidates, joined;
  for (const ThermalPerson& person : *people) {
    const cv::Rect& b = person.bbox;
    for (int y = b.y; y < b.y + b.height; ++y) {
      const std::uint8_t* row = ids->ptr<std::uint8_t>(y);
      for (int x = b.x; x < b.x + b.width; ++x) {
        if (row[x] != 0) addZeroNeighbours(*ids, cv::Point(x, y), &seen, &candidates);
      }
    }
  }
  std::vector<std::uint8_t> chosen;
  for (int step = 0; step < steps && !candidates.empty(); ++step) {
    joined.clear();
    chosen.clear();
    for (const cv::Point& q : candidates) {
      seen.at<std::uint8_t>(q) = 0;
      if (warm.at<std::uint8_t>(q) == 0 || (!regions.empty() && regions.at<std::uint8_t>(q) != 0)) continue;
      int id = 256;
      forEachNeighbour(q, ids->size(), [&](const cv::Point& n) {
        const int v = ids->at<std::uint8_t>(n);
        if (v != 0) id = std::min(id, v);
      });
      if (id == 256 || image.at<T>(q) < floors[static_cast<std::size_t>(id - 1)]) continue;
      joined.push_back(q);
      chosen.push_back(static_cast<std::uint8_t>(id));
    }
    // Written after the step, so that every pixel of it saw the people as they were before it.
    for (std::size_t k = 0; k < joined.size(); ++k) {
      ids->at<std::uint8_t>(joined[k]) = chosen[k];
      ThermalPerson& person = (*people)[chosen[k] - 1u];
      person.bbox |= cv::Rect(joined[k], cv::Size(1, 1));
      ++person.area_px;
    }
    candidates.clear();
    for (const cv::Point& p : joined) addZeroNeighbours(*ids, p, &seen, &candidates);
  }
}

}  // namespace

void restoreOpenedParts(const cv::Mat& image, const cv::Mat& warm, const cv::Mat& regions, int steps,
                        const std::vector<double>& floors, cv::Mat* ids, std::vector<ThermalPerson>* people) {
  if (steps <= 0 || people->empty()) return;
  if (image.depth() == CV_16U) {
    grow<std::uint16_t>(image, warm, regions, steps, floors, ids, people);
  } else {
    grow<std::uint8_t>(image, warm, regions, steps, floors, ids, people);
  }
}

}  // namespace detection
}  // namespace thermal_lidar_calibration
