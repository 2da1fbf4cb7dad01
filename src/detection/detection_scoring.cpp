#include "thermal_lidar_calibration/detection/detection_scoring.hpp"

#include <algorithm>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <tuple>

namespace thermal_lidar_calibration {
namespace detection {
namespace {

std::uint32_t pixelId(const cv::Mat& m, int y, int x) {
  return m.depth() == CV_16U ? m.at<std::uint16_t>(y, x) : m.at<std::uint8_t>(y, x);
}

// The matching shared by both modalities. overlap[d][t] = what detection d shares with truth t
// (t = 0: background); `quality(d, t)` is the match measure (IoU or purity), `threshold` its
// minimum.
template <typename Quality>
FrameScore matchDetections(const std::map<std::uint32_t, std::map<std::uint32_t, long>>& overlap,
                           const std::vector<TruthPerson>& people, Quality quality, double threshold) {
  std::set<std::uint32_t> scored;
  for (const TruthPerson& p : people) {
    if (p.scored && p.id > 0) scored.insert(p.id);
  }
  FrameScore score;
  score.scored_people = static_cast<int>(scored.size());
  // Candidate pairs above the threshold, best first (ties by ids: deterministic).
  std::vector<std::tuple<double, std::uint32_t, std::uint32_t>> pairs;
  for (const auto& [d, row] : overlap) {
    for (const auto& [t, shared] : row) {
      if (t == 0 || shared <= 0) continue;
      const double q = quality(d, t);
      if (q >= threshold) pairs.emplace_back(q, d, t);
    }
  }
  std::sort(pairs.begin(), pairs.end(), [](const auto& a, const auto& b) {
    if (std::get<0>(a) != std::get<0>(b)) return std::get<0>(a) > std::get<0>(b);
    return std::make_pair(std::get<1>(a), std::get<2>(a)) < std::make_pair(std::get<1>(b), std::get<2>(b));
  });
  std::map<std::uint32_t, std::uint32_t> match;  // detection -> truth
  std::set<std::uint32_t> taken;
  for (const auto& [q, d, t] : pairs) {
    if (match.count(d) || taken.count(t)) continue;
    match[d] = t;
    taken.insert(t);
  }
  for (const auto& [d, row] : overlap) {
    // The person this detection mostly covers (background counts as id 0).
    std::uint32_t majority = 0;
    long best = -1;
    for (const auto& [t, shared] : row) {
      if (shared > best) {
        best = shared;
        majority = t;
      }
    }
    const auto m = match.find(d);
    const std::uint32_t owner = m != match.end() ? m->second : majority;
    if (owner != 0 && !scored.count(owner)) {
      ++score.ignored;
    } else if (m != match.end()) {
      ++score.true_positives;
    } else {
      ++score.false_positives;
      score.false_detections.push_back({d, majority});
    }
  }
  for (std::uint32_t t : scored) {
    if (!taken.count(t)) {
      ++score.false_negatives;
      score.missed_people.push_back(t);
    }
  }
  score.detected = score.true_positives + score.false_positives;
  return score;
}

}  // namespace

void DetectionScore::add(const FrameScore& f) {
  true_positives += f.true_positives;
  false_positives += f.false_positives;
  false_negatives += f.false_negatives;
  ignored += f.ignored;
  ++frames;
  frames_counts_agree += f.countsAgree() ? 1 : 0;
}

void DetectionScore::add(const DetectionScore& o) {
  true_positives += o.true_positives;
  false_positives += o.false_positives;
  false_negatives += o.false_negatives;
  ignored += o.ignored;
  frames += o.frames;
  frames_counts_agree += o.frames_counts_agree;
}

double DetectionScore::recall() const {
  const long n = true_positives + false_negatives;
  return n > 0 ? static_cast<double>(true_positives) / n : 1.0;
}
double DetectionScore::precision() const {
  const long n = true_positives + false_positives;
  return n > 0 ? static_cast<double>(true_positives) / n : 1.0;
}
double DetectionScore::countAgreement() const {
  return frames > 0 ? static_cast<double>(frames_counts_agree) / frames : 1.0;
}

FrameScore scoreMask(const cv::Mat& detected, const cv::Mat& truth_ids, const std::vector<TruthPerson>& people,
                     double min_iou) {
  if (detected.type() != CV_8UC1) throw std::invalid_argument("scoreMask: the detected mask must be CV_8UC1");
  if (truth_ids.type() != CV_16UC1 && truth_ids.type() != CV_8UC1) {
    throw std::invalid_argument("scoreMask: the truth id image must be CV_16UC1 or CV_8UC1");
  }
  if (detected.size() != truth_ids.size()) {
    throw std::invalid_argument("scoreMask: mask " + std::to_string(detected.cols) + "x" +
                                std::to_string(detected.rows) + " and truth " + std::to_string(truth_ids.cols) +
                                "x" + std::to_string(truth_ids.rows) + " differ in size");
  }
  std::map<std::uint32_t, std::map<std::uint32_t, long>> overlap;
  std::map<std::uint32_t, long> truth_area, detected_area;
  for (int y = 0; y < detected.rows; ++y) {
    const std::uint8_t* d = detected.ptr<std::uint8_t>(y);
    for (int x = 0; x < detected.cols; ++x) {
      const std::uint32_t t = pixelId(truth_ids, y, x);
      if (t != 0) ++truth_area[t];
      if (d[x] == 0) continue;
      ++detected_area[d[x]];
      ++overlap[d[x]][t];
    }
  }
  auto iou = [&](std::uint32_t d, std::uint32_t t) {
    const double inter = static_cast<double>(overlap[d][t]);
    return inter / (static_cast<double>(detected_area[d] + truth_area[t]) - inter);
  };
  return matchDetections(overlap, people, iou, min_iou);
}

FrameScore scoreClusters(const std::vector<std::uint32_t>& cluster_labels,
                         const std::vector<std::uint32_t>& point_truth, const std::vector<TruthPerson>& people,
                         double min_purity) {
  if (cluster_labels.size() != point_truth.size()) {
    throw std::invalid_argument("scoreClusters: " + std::to_string(cluster_labels.size()) + " labels but " +
                                std::to_string(point_truth.size()) + " truth ids");
  }
  std::map<std::uint32_t, std::map<std::uint32_t, long>> overlap;
  std::map<std::uint32_t, long> size;
  for (std::size_t i = 0; i < cluster_labels.size(); ++i) {
    ++overlap[cluster_labels[i]][point_truth[i]];
    ++size[cluster_labels[i]];
  }
  auto purity = [&](std::uint32_t d, std::uint32_t t) {
    return static_cast<double>(overlap[d][t]) / static_cast<double>(size[d]);
  };
  return matchDetections(overlap, people, purity, min_purity);
}

bool whollyInView(const cv::Mat& truth_ids, std::uint32_t id) {
  bool any = false;
  for (int y = 0; y < truth_ids.rows; ++y) {
    const bool edge_row = y == 0 || y == truth_ids.rows - 1;
    for (int x = 0; x < truth_ids.cols; ++x) {
      if (pixelId(truth_ids, y, x) != id) continue;
      if (edge_row || x == 0 || x == truth_ids.cols - 1) return false;
      any = true;
    }
  }
  return any;
}

}  // namespace detection
}  // namespace thermal_lidar_calibration
