#include "detection_explain.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

namespace thermal_lidar_calibration {
namespace bench {
namespace {

constexpr double kMinIou = 0.5;     // the scorer's thermal match
constexpr double kMinPurity = 0.8;  // the scorer's LiDAR match

double iou(const cv::Rect& a, const cv::Rect& b) {
  const double inter = (a & b).area();
  return inter <= 0 ? 0.0 : inter / (a.area() + b.area() - inter);
}

double aspectOf(const cv::Rect& box) { return static_cast<double>(box.height) / std::max(1, box.width); }

}  // namespace

void explainThermal(std::FILE* out, double stamp_s, const detection::ThermalSegmentation& segmentation,
                    const cv::Mat& detected_mask, const cv::Mat& truth_ids, const std::vector<std::uint32_t>& scored) {
  // Pixel overlaps: detected id x truth id (0 = background), and each truth person's box.
  std::map<int, std::map<std::uint32_t, long>> overlap;
  std::map<std::uint32_t, long> truth_area;
  std::map<std::uint32_t, cv::Rect> truth_box;
  for (int v = 0; v < truth_ids.rows; ++v) {
    for (int u = 0; u < truth_ids.cols; ++u) {
      const std::uint32_t t = truth_ids.at<std::uint16_t>(v, u);
      const int d = detected_mask.at<std::uint8_t>(v, u);
      if (t != 0) {
        ++truth_area[t];
        auto it = truth_box.find(t);
        if (it == truth_box.end()) {
          truth_box[t] = cv::Rect(u, v, 1, 1);
        } else {
          it->second |= cv::Rect(u, v, 1, 1);
        }
      }
      if (d != 0) ++overlap[d][t];
    }
  }
  auto pixel_iou = [&](int d, std::uint32_t t) {
    long d_area = 0;
    for (const auto& [id, n] : overlap[d]) d_area += n;
    const long inter = overlap[d].count(t) ? overlap[d][t] : 0;
    return static_cast<double>(inter) / static_cast<double>(d_area + truth_area[t] - inter);
  };
  const std::set<std::uint32_t> scored_set(scored.begin(), scored.end());
  for (std::uint32_t t : scored) {
    bool found = false;
    for (const auto& person : segmentation.people) found = found || pixel_iou(person.id, t) >= kMinIou;
    if (found) continue;
    const cv::Rect& box = truth_box[t];
    std::fprintf(out, "thermal miss  t=%.1f person %u box %dx%d at (%d,%d) h/w %.2f:", stamp_s, t, box.width,
                 box.height, box.x, box.y, aspectOf(box));
    // What the detector made of the place: the detection or rejected region overlapping it most.
    const detection::ThermalPerson* best_person = nullptr;
    const detection::RejectedRegion* best_rejected = nullptr;
    double best = 0.0;
    for (const auto& p : segmentation.people) {
      if (iou(p.bbox, box) > best) best = iou(p.bbox, box), best_person = &p, best_rejected = nullptr;
    }
    for (const auto& r : segmentation.rejected) {
      if (iou(r.bbox, box) > best) best = iou(r.bbox, box), best_rejected = &r, best_person = nullptr;
    }
    if (best_person) {
      std::fprintf(out, " detected as %dx%d (box IoU %.2f, pixel IoU %.2f)\n", best_person->bbox.width,
                   best_person->bbox.height, best, pixel_iou(best_person->id, t));
    } else if (best_rejected) {
      std::fprintf(out, " rejected %s %dx%d h/w %.2f fill %.2f legs/torso %.2f (box IoU %.2f)\n",
                   best_rejected->reason.c_str(), best_rejected->bbox.width, best_rejected->bbox.height,
                   aspectOf(best_rejected->bbox),
                   static_cast<double>(best_rejected->area_px) / best_rejected->bbox.area(),
                   best_rejected->leg_to_torso_width, best);
    } else {
      std::fprintf(out, " no warm region there\n");
    }
  }
  for (const auto& p : segmentation.people) {
    std::uint32_t owner = 0;
    long most = -1;
    bool matched = false;
    for (const auto& [t, n] : overlap[p.id]) {
      matched = matched || (t != 0 && pixel_iou(p.id, t) >= kMinIou);
      if (n > most) most = n, owner = t;
    }
    if (matched || (owner != 0 && !scored_set.count(owner))) continue;
    std::fprintf(out,
                 "thermal false t=%.1f box %dx%d at (%d,%d) h/w %.2f fill %.2f legs/torso %.2f mean %.1f; "
                 "mostly %s\n",
                 stamp_s, p.bbox.width, p.bbox.height, p.bbox.x, p.bbox.y, aspectOf(p.bbox), p.fill,
                 p.leg_to_torso_width, p.mean_level,
                 owner == 0 ? "no person (a confounder)" : "a scored person, matched poorly");
  }
}

void explainLidar(std::FILE* out, double stamp_s, const detection::LidarDetection& detection,
                  const std::vector<Eigen::Vector3f>& points, const std::vector<std::uint32_t>& truth,
                  const std::vector<std::uint32_t>& scored) {
  // Per detected label: truth id -> points.
  std::map<std::uint32_t, std::map<std::uint32_t, int>> shares;
  for (std::size_t k = 0; k < detection.labels.size(); ++k) {
    ++shares[detection.labels[k]][truth[static_cast<std::size_t>(detection.indices[k])]];
  }
  auto purity_owner = [&](std::uint32_t label, double* purity) {
    int total = 0, most = -1;
    std::uint32_t owner = 0;
    for (const auto& [t, n] : shares[label]) {
      total += n;
      if (n > most) most = n, owner = t;
    }
    *purity = total > 0 ? static_cast<double>(most) / total : 0.0;
    return owner;
  };
  const std::set<std::uint32_t> scored_set(scored.begin(), scored.end());
  std::set<std::uint32_t> matched;
  for (const auto& person : detection.people) {
    double purity = 0;
    const std::uint32_t owner = purity_owner(person.label, &purity);
    if (owner != 0 && purity >= kMinPurity) {
      matched.insert(owner);
      continue;
    }
    if (owner != 0 && !scored_set.count(owner)) continue;
    std::fprintf(out, "lidar false   t=%.1f range %.1f m height %.2f width %.2f points %d; purity %.2f of %s\n",
                 stamp_s, person.range_m, person.height_m, person.width_m, person.point_count, purity,
                 owner == 0 ? "no person" : "a scored person");
  }
  for (std::uint32_t t : scored) {
    if (matched.count(t)) continue;
    Eigen::Vector3f sum = Eigen::Vector3f::Zero();
    int n = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (truth[i] == t) sum += points[i], ++n;
    }
    const Eigen::Vector3f c = sum / static_cast<float>(std::max(n, 1));
    std::fprintf(out, "lidar miss    t=%.1f person %u range %.1f m bearing %.0f deg points %d:", stamp_s, t,
                 std::hypot(c.x(), c.y()), std::atan2(c.y(), c.x()) * 180.0 / M_PI, n);
    // The rejected object holding most of this person's points.
    const detection::RejectedObject* best = nullptr;
    int best_n = 0;
    for (const auto& r : detection.rejected) {
      int mine = 0;
      for (int i : r.indices) mine += truth[static_cast<std::size_t>(i)] == t ? 1 : 0;
      if (mine > best_n) best_n = mine, best = &r;
    }
    if (best == nullptr) {
      std::fprintf(out, " in no object (ground or merged into a detection)\n");
      continue;
    }
    const detection::PersonShape& s = best->shape;
    std::fprintf(out,
                 " %s (%d of its points in an object of %d) top %.2f bottom %.2f width %.2f depth %.2f "
                 "legs/torso %.2f\n",
                 detection::toString(best->verdict), best_n, s.points, s.top_m, s.bottom_m, s.width_m, s.depth_m,
                 s.leg_to_torso_width);
  }
}

}  // namespace bench
}  // namespace thermal_lidar_calibration
