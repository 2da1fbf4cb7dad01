#pragma once
// The one ingest path shared by calibration_node and calibrate_bag: candidate frame ->
// skip rule -> decode -> validation against the camera -> people counts -> gate -> pair.

#include "thermal_lidar_calibration/core/calibration_pair.hpp"
#include "thermal_lidar_calibration/core/camera_model.hpp"
#include "thermal_lidar_calibration/core/frame_gate.hpp"

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace thermal_lidar_calibration {

struct OfferOutcome {
  GateDecision decision = GateDecision::kSkipped;
  std::string error;  // for kBadMessage: what was wrong, one line, user-actionable
  int mask_people = 0;
  int cluster_people = 0;
};

// Frames whose ids keep disagreeing with the ids the dataset is locked to (see DatasetBuilder).
struct FrameIdConflict {
  std::string camera_frame, lidar_frame;              // the dataset's (locked) ids
  std::string other_camera_frame, other_lidar_frame;  // the latest disagreeing frame's ids
  std::uint64_t frames_in_a_row = 0;                  // valid frames refused in a row for them
};

// Frame ids: one dataset holds one pair of sensors, so frames with other ids are refused. But a
// single frame must not decide the ids of a drive (one stray frame first would block the whole
// drive): until kLockPairs pairs are kept, the ids are tentative, and when valid frames with other
// ids outnumber the frames that support the tentative ids, the builder switches to those ids
// and drops the few pairs it had (counted in pairsDroppedForFrameIds()). Once locked, frames
// with other ids are refused, and frameIdConflict() reports when they keep coming.
class DatasetBuilder {
 public:
  static constexpr std::size_t kLockPairs = 3;

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
  // Hands over the kept pairs and forgets them, keeping the counts and the frame ids (the drift
  // watch takes each pair as it is kept and must not hold hours of them here).
  std::vector<CalibrationPair> takePairs();

  const std::vector<CalibrationPair>& pairs() const { return pairs_; }
  const RejectionCounts& counts() const { return gate_.counts(); }
  const CameraModel& camera() const { return camera_; }
  const std::string& cameraFrame() const { return camera_frame_; }
  const std::string& lidarFrame() const { return lidar_frame_; }
  bool frameIdsLocked() const { return ids_locked_; }
  std::uint64_t pairsDroppedForFrameIds() const { return pairs_dropped_for_ids_; }
  // Set when at least `min_in_a_row` valid frames in a row had other ids than the locked ones.
  std::optional<FrameIdConflict> frameIdConflict(std::uint64_t min_in_a_row = 10) const;

 private:
  using FrameIds = std::pair<std::string, std::string>;  // camera, lidar
  OfferOutcome admit(const std::function<Frame()>& decode, bool stored);
  // Throws std::invalid_argument when `frame`'s ids are refused; may switch tentative ids.
  void checkFrameIds(const Frame& frame);

  CameraModel camera_;
  FrameGate gate_;
  std::vector<CalibrationPair> pairs_;
  std::string camera_frame_, lidar_frame_;
  bool ids_locked_ = false;
  std::uint64_t tentative_support_ = 0;         // valid frames with the tentative ids
  std::map<FrameIds, std::uint64_t> other_ids_;  // valid frames with other ids, while tentative
  std::uint64_t pairs_dropped_for_ids_ = 0;
  std::uint64_t refused_in_a_row_ = 0;
  FrameIds last_refused_;
};

}  // namespace thermal_lidar_calibration
