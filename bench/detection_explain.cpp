#include "detection_explain.hpp"

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

namespace thermal_lidar_calibration {
namespace bench {
namespace {

double boxIou(const cv::Rect& a, const cv::Rect& b) {
  const double inter = (a & b).area();
  return inter <= 0 ? 0.0 : inter / (a.area() + b.area() - inter);
}

double aspectOf(const cv::Rect& box) { return static_cast<double>(box.height) / std::max(1, box.width); }

// IoU of detection `d` in `detected` with person `t` in `truth_ids`, pixel by pixel.
double pixelIou(const cv::Mat& detected, int d, const cv::Mat& truth_ids, std::uint32_t t) {
  const cv::Mat a = detected == d, b = truth_ids == static_cast<double>(t);
  const int inter = cv::countNonZero(a & b), uni = cv::countNonZero(a | b);
  return uni > 0 ? static_cast<double>(inter) / uni : 0.0;
}

}  // namespace

void explainThermal(std::FILE* out, double stamp_s, const detection::ThermalSegmentation& segmentation,
                    const detection::FrameScore& score, const cv::Mat& detected_mask, const cv::Mat& truth_ids) {
  for (std::uint32_t t : score.missed_people) {
    const cv::Rect box = cv::boundingRect(truth_ids == static_cast<double>(t));
    std::fprintf(out, "thermal miss  t=%.1f person %u box %dx%d at (%d,%d) h/w %.2f:", stamp_s, t, box.width,
                 box.height, box.x, box.y, aspectOf(box));
    // What the detector made of the place: the detection or rejected region overlapping it most.
    const detection::ThermalPerson* best_person = nullptr;
    const detection::RejectedRegion* best_rejected = nullptr;
    double best = 0.0;
    for (const auto& p : segmentation.people) {
      if (boxIou(p.bbox, box) > best) best = boxIou(p.bbox, box), best_person = &p, best_rejected = nullptr;
    }
    for (const auto& r : segmentation.rejected) {
      if (boxIou(r.bbox, box) > best) best = boxIou(r.bbox, box), best_rejected = &r, best_person = nullptr;
    }
    if (best_person) {
      std::fprintf(out, " detected as %dx%d (box IoU %.2f, pixel IoU %.2f)\n", best_person->bbox.width,
                   best_person->bbox.height, best, pixelIou(detected_mask, best_person->id, truth_ids, t));
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
  for (const auto& f : score.false_detections) {
    const auto p = std::find_if(segmentation.people.begin(), segmentation.people.end(),
                                [&](const detection::ThermalPerson& q) { return q.id == static_cast<int>(f.detection); });
    if (p == segmentation.people.end()) continue;
    std::fprintf(out,
                 "thermal false t=%.1f box %dx%d at (%d,%d) h/w %.2f fill %.2f legs/torso %.2f mean %.1f; "
                 "mostly %s\n",
                 stamp_s, p->bbox.width, p->bbox.height, p->bbox.x, p->bbox.y, aspectOf(p->bbox), p->fill,
                 p->leg_to_torso_width, p->mean_level,
                 f.majority == 0 ? "no person (a confounder)" : "a scored person, matched poorly");
  }
}

void explainLidar(std::FILE* out, double stamp_s, const detection::LidarDetection& detection,
                  const detection::FrameScore& score, const std::vector<Eigen::Vector3f>& points,
                  const std::vector<std::uint32_t>& truth) {
  for (const auto& f : score.false_detections) {
    const auto person = std::find_if(detection.people.begin(), detection.people.end(),
                                     [&](const auto& q) { return q.label == f.detection; });
    if (person == detection.people.end()) continue;
    int total = 0, majority = 0;
    for (std::size_t k = 0; k < detection.labels.size(); ++k) {
      if (detection.labels[k] != f.detection) continue;
      ++total;
      majority += truth[static_cast<std::size_t>(detection.indices[k])] == f.majority ? 1 : 0;
    }
    std::fprintf(out, "lidar false   t=%.1f range %.1f m height %.2f width %.2f points %d; purity %.2f of %s\n",
                 stamp_s, person->range_m, person->height_m, person->width_m, person->point_count,
                 total > 0 ? static_cast<double>(majority) / total : 0.0,
                 f.majority == 0 ? "no person" : "a scored person");
  }
  for (std::uint32_t t : score.missed_people) {
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
