#pragma once
// The one ingest path shared by calibration_node and calibrate_bag: candidate frame ->
// skip rule -> decode -> validation against the camera -> people counts -> gate -> pair.

#include "thermal_lidar_calibration/core/calibration_pair.hpp"
#include "thermal_lidar_calibration/core/camera_model.hpp"
#include "thermal_lidar_calibration/core/frame_gate.hpp"

#include <functional>
#include <string>
#include <vector>

namespace thermal_lidar_calibration {

struct OfferOutcome {
  GateDecision decision = GateDecision::kSkipped;
  std::string error;  // for kBadMessage: what was wrong, one line, user-actionable
  int mask_people = 0;
  int cluster_people = 0;
};

class DatasetBuilder {
 public:
  DatasetBuilder(CameraModel camera, GateConfig config);

  // Offer one synchronized candidate frame. `decode` runs only if the frame is not skipped; it
  // may throw std::invalid_argument (counted as kBadMessage, the message returned in `error`).
  // The decoded frame's mask must match the camera size, else kBadMessage.
  OfferOutcome offer(const std::function<Frame()>& decode);

  // A frame kept in an earlier session (reloaded from a dataset bag for ~resume): the same
  // checks and counting as offer(), but no skip or count rule (it was kept under them once).
  // kKept, or kBadMessage with the reason (e.g. recorded with a different camera).
  OfferOutcome restore(Frame frame);
  void reset();  // forget pairs and counts

  const std::vector<CalibrationPair>& pairs() const { return pairs_; }
  const RejectionCounts& counts() const { return gate_.counts(); }
  const CameraModel& camera() const { return camera_; }
  const std::string& cameraFrame() const { return camera_frame_; }
  const std::string& lidarFrame() const { return lidar_frame_; }

 private:
  OfferOutcome admit(const std::function<Frame()>& decode, bool stored);

  CameraModel camera_;
  FrameGate gate_;
  std::vector<CalibrationPair> pairs_;
  std::string camera_frame_, lidar_frame_;
};

}  // namespace thermal_lidar_calibration
