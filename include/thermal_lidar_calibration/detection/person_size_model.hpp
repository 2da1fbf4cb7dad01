#pragma once
// The ground-plane size check of the thermal segmenter. People stand on the ground, so the lower
// their feet are in the image the taller they look: for a camera h above flat ground, a person
// H tall whose feet are at row v_f looks about (H / h) (v_f - v_h) px tall, v_h the horizon's
// row, whatever the focal length (and for tilts of a few tens of degrees). The model learns the
// slope k = H / h and v_h from the candidates the shape filters passed in recent frames (people
// are most of them) and flags a candidate much shorter than a person standing where its feet
// are: an animal seen end on (about half a person's height) passes every shape filter but not
// this. Nothing is learned about the camera from outside; with too few or too alike candidates
// (one distance only) the model stays unready and flags nothing.

#include "thermal_lidar_calibration/detection/thermal_person_segmenter.hpp"

#include <opencv2/core.hpp>

#include <cstddef>
#include <deque>
#include <optional>
#include <vector>

namespace thermal_lidar_calibration {
namespace detection {

struct PersonSizeFit {
  double horizon_row = 0;  // v_h, px (may be above the image)
  double slope = 0;        // k: px of person height per px of foot row below the horizon
  int support = 0;         // candidates within the people's band of this fit
  int samples = 0;         // candidates the fit saw
};

class PersonSizeModel {
 public:
  // Uses thermal_size_history, thermal_size_min_samples and thermal_size_min_ratio.
  explicit PersonSizeModel(const ThermalSegmenterConfig& config = {});

  // Adds one frame's candidates (bounding boxes of the regions that passed the shape filters)
  // and refits every few frames. Deterministic: the same frames in the same order give the same
  // fits.
  void observe(const std::vector<cv::Rect>& boxes);

  // The current fit, when the model is ready to judge.
  const std::optional<PersonSizeFit>& fit() const { return fit_; }

  // The box's height over the height a person has at its foot row; empty while the model is not
  // ready or when the feet are too near (or above) the horizon to judge.
  std::optional<double> heightRatio(const cv::Rect& box) const;

  // heightRatio below min_ratio.
  bool tooShortForItsRange(const cv::Rect& box) const;

 private:
  void refit();

  int history_;
  int min_samples_;
  double min_ratio_;
  std::deque<cv::Point2f> samples_;  // (foot row, height) per candidate, oldest first
  int frames_since_fit_ = 0;
  std::optional<PersonSizeFit> fit_;
};

// One frame through the check: the people `model` finds too short for their foot row move to
// `rejected` ("too_short_for_range") and leave the mask, the rest are renumbered 1..n in order;
// then the model sees all of this frame's candidates (judged by the frames before it).
void applySizeCheck(ThermalSegmentation& segmentation, PersonSizeModel& model);

}  // namespace detection
}  // namespace thermal_lidar_calibration
