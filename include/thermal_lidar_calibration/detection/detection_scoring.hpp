#pragma once
// Detection quality against per-pixel / per-point truth, per modality:
//  - a mask instance matches a person when their IoU >= min_iou (0.5);
//  - a cluster matches a person when >= min_purity (80 %) of its points are that person's;
// one detection per person (a second match of the same person is a false positive). Only the
// people marked `scored` count (the rule: within 20 m and wholly in view); a detection
// that belongs to a person who is not scored (too far, cut by the image border) is ignored,
// neither true nor false. A frame's counts agree when the detections that are not ignored
// number the scored people.

#include <opencv2/core.hpp>

#include <cstdint>
#include <vector>

namespace thermal_lidar_calibration {
namespace detection {

struct TruthPerson {
  std::uint32_t id = 0;  // the truth id (> 0) in the id image / per-point ids
  bool scored = false;
};

struct FrameScore {
  int true_positives = 0;
  int false_positives = 0;
  int false_negatives = 0;  // scored people without a matching detection
  int ignored = 0;          // detections of people who are not scored
  int detected = 0;         // detections that are not ignored (TP + FP)
  int scored_people = 0;
  // Which ones, for explaining a score (score_raw_detections --explain): the scored people
  // without a matching detection, and each detection counted false with the truth id it mostly
  // covers (0 = background: a confounder; else a scored person it matched too poorly).
  std::vector<std::uint32_t> missed_people;
  struct FalseDetection {
    std::uint32_t detection = 0;
    std::uint32_t majority = 0;
  };
  std::vector<FalseDetection> false_detections;
  bool countsAgree() const { return detected == scored_people; }
};

struct DetectionScore {
  long true_positives = 0;
  long false_positives = 0;
  long false_negatives = 0;
  long ignored = 0;
  long frames = 0;
  long frames_counts_agree = 0;
  void add(const FrameScore& frame);
  void add(const DetectionScore& other);
  double recall() const;        // TP / (TP + FN); 1 when nobody was scored
  double precision() const;     // TP / (TP + FP); 1 when nothing was detected
  double countAgreement() const;  // share of frames whose counts agree; 1 when no frame
};

// detected: CV_8UC1 instance mask (0 = background); truth_ids: CV_16UC1 (or CV_8UC1) person ids
// of the same size. People present in truth_ids but not listed are treated as not scored.
// Throws std::invalid_argument on a size or type mismatch.
FrameScore scoreMask(const cv::Mat& detected, const cv::Mat& truth_ids, const std::vector<TruthPerson>& people,
                     double min_iou = 0.5);

// cluster_labels: the detected label of each detected point; point_truth: that point's truth id
// (0 = not a person). Throws std::invalid_argument when the sizes differ.
FrameScore scoreClusters(const std::vector<std::uint32_t>& cluster_labels,
                         const std::vector<std::uint32_t>& point_truth, const std::vector<TruthPerson>& people,
                         double min_purity = 0.8);

// True when person `id` has pixels in truth_ids and none of them on the image border.
bool whollyInView(const cv::Mat& truth_ids, std::uint32_t id);

}  // namespace detection
}  // namespace thermal_lidar_calibration
