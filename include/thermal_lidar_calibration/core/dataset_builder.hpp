#pragma once
// The one ingest path shared by calibration_node and calibrate_bag: candidate frame ->
// skip rule -> decode -> validation against the camera -> people counts -> gate -> pair.

#include "thermal_lidar_calibration/core/calibration_pair.hpp"
#include "thermal_lidar_calibration/core/camera_model.hpp"
#include "thermal_lidar_calibration/core/frame_gate.hpp"
#include "thermal_lidar_calibration/core/person_motion.hpp"

#include <cstdint>
#include <deque>
#include <functional>
#include <limits>
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
  // Issue 23: the count rule did not keep the frame, but it is a candidate for pairing by
  // association (held, or waiting for its people's motion; held only if the bound allows).
  bool candidate = false;
  std::uint64_t frame_index = 0;  // its place among the frames offered (candidate_index)
  // Issue 24: a frame the skip rule passed over (kSkipped) was decoded for the final round and
  // is held, or waits for its people's motion (keepSkippedFrames).
  bool skipped_held = false;
};

// How a frame stored by an earlier session (a dataset bag) was kept there.
struct StoredFrameKind {
  bool candidate = false;  // held for association, not kept by the count rule
  // Its candidate_index in that session: the skip rule between association pairs and the pairs
  // of either rule counts in it. Unknown in dataset bags written before it was recorded: the
  // stored frames are then numbered in order, as if offered one after another.
  std::optional<std::uint64_t> frame_index;
  // Issue 24: a frame the skip rule passed over, held for the association's final round (with
  // `candidate`): restored as one when the builder keeps skipped frames, left out otherwise.
  bool skipped = false;
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
//
// People's motion (issue 21): with a MotionConfig, every scan of person clusters is observed
// (observeScan, kept frames or not), and a kept pair waits (pendingPairs) until window_scans
// later scans have arrived, then gets each person's velocity from the scans around it
// (person_motion.hpp) and joins pairs(). A frame that already carries velocities (a dataset bag
// the node wrote) is kept as it is.
class DatasetBuilder {
 public:
  static constexpr std::size_t kLockPairs = 3;

  DatasetBuilder(CameraModel camera, GateConfig config,
                 std::optional<MotionConfig> motion = std::nullopt);

  // Offer one synchronized candidate frame. `decode` runs only if the frame is not skipped; it
  // may throw std::invalid_argument (counted as kBadMessage, the message returned in `error`).
  // The decoded frame's mask must match the camera size, else kBadMessage.
  OfferOutcome offer(const std::function<Frame()>& decode);

  // A frame kept in an earlier session (reloaded from a dataset bag for ~resume): the same
  // checks and counting as offer(), but no skip or count rule (it was kept under them once).
  // kKept, or kBadMessage with the reason (e.g. recorded with a different camera). A stored
  // association candidate is held as a candidate again (outcome.candidate; the decision is what
  // the count rule says of it) when this builder keeps candidates, and left out otherwise; one
  // that today's count rule keeps (H_max raised, say) becomes a pair of that rule.
  OfferOutcome restore(Frame frame, const StoredFrameKind& kind = {});
  void reset();  // forget pairs, counts, waiting pairs and scans

  // Every scan of person clusters, in time order (a late one is put in its place). Finishes the
  // waiting pairs whose later scans are now there. Without a MotionConfig it does nothing.
  void observeScan(ScanPeople scan);
  std::size_t pendingPairs() const { return pending_.size(); }
  // No more scans will come (the end of a bag): the waiting pairs get the motion the scans
  // there are show, and join pairs().
  void flushPending();
  bool tracksMotion() const { return motion_.has_value(); }
  // The newest scan's people measured from the scans before it only (for a live overlay, which
  // cannot wait for the next scan); empty without scans or a MotionConfig.
  std::vector<PersonMotion> latestMotion() const;
  double latestScanStamp() const { return scans_.empty() ? 0.0 : scans_.back().stamp_s; }
  // Hands over the kept pairs and forgets them, keeping the counts and the frame ids (the drift
  // watch takes each pair as it is kept and must not hold hours of them here).
  std::vector<CalibrationPair> takePairs();

  // Issue 23: also keep the decoded frames the count rule did not keep but that show people in
  // both modalities (unequal counts, more than H_max, a small cluster), as candidates for pairing
  // by association once an extrinsic is known (skipped frames: keepSkippedFrames). Off by default (the
  // paper keeps nothing else). `max_candidates` bounds the memory (a candidate holds a decoded
  // image and its regions): when one more would pass it, every second candidate held is dropped,
  // and from then on only every second (then fourth, ...) new one is kept, so those held stay
  // spread evenly over the drive (the node collects for as long as it runs).
  void keepAssociationCandidates(bool keep,
                                 std::size_t max_candidates = std::numeric_limits<std::size_t>::max());
  bool keepsAssociationCandidates() const { return keep_candidates_; }
  // Candidates dropped or passed over for max_candidates since the start (or reset()).
  std::uint64_t candidatesDropped() const { return candidates_dropped_; }
  // The candidates (rule kAssociation, regions set, mask empty), in time order, handed over;
  // the next ones are spaced (max_candidates) among themselves.
  std::vector<CalibrationPair> takeCandidates();
  const std::vector<CalibrationPair>& candidates() const { return candidates_.held; }

  // Issue 24: while candidates are kept, also decode the frames the skip rule passes over and
  // hold those with people in both modalities (outside_skip_rule set, otherwise candidates
  // like the others), apart from the candidates, under the same bound: the association's final
  // round pairs them (association_refit.hpp). The skip rule, the gate's counts and the drift
  // watch see them as skipped, as before; a skipped frame that cannot be decoded, or with other
  // frame ids, is left out without a word (it was never going to be kept).
  void keepSkippedFrames(bool keep) { keep_skipped_ = keep; }
  bool keepsSkippedFrames() const { return keep_candidates_ && keep_skipped_; }
  const std::vector<CalibrationPair>& skippedFrames() const { return skipped_.held; }
  std::vector<CalibrationPair> takeSkippedFrames();

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
  OfferOutcome admit(const std::function<Frame()>& decode, bool stored, const StoredFrameKind& kind = {});
  // Throws std::invalid_argument when `frame`'s ids are refused; may switch tentative ids.
  void checkFrameIds(const Frame& frame);

  CameraModel camera_;
  FrameGate gate_;
  std::vector<CalibrationPair> pairs_;
  // Frames held under a bound, spread evenly over the drive (keepAssociationCandidates).
  struct SpacedFrames {
    std::vector<CalibrationPair> held;
    std::uint64_t seen = 0;    // frames that reached add(), held or not
    std::uint64_t stride = 1;  // hold every stride-th of them (doubles when full)
    // Holds `pair` or passes over it; returns the frames dropped or passed over.
    std::uint64_t add(CalibrationPair pair, std::size_t bound);
    std::vector<CalibrationPair> take();  // hands `held` over; the next ones are spaced anew
  };
  bool keep_candidates_ = false;
  bool keep_skipped_ = false;
  SpacedFrames candidates_;
  SpacedFrames skipped_;
  std::size_t max_candidates_ = std::numeric_limits<std::size_t>::max();
  std::uint64_t candidates_dropped_ = 0;
  // A frame the skip rule passes over, decoded and held when keepsSkippedFrames().
  bool holdSkippedFrame(const std::function<Frame()>& decode, std::uint64_t index);  // held or waiting
  // A decoded frame as a pair of `rule` (kAssociation: a candidate), through the wait for its
  // people's motion when there is one, into pairs(), candidates() or skippedFrames().
  void hold(Frame frame, std::uint64_t index, PairRule rule, int people, bool skipped);
  std::uint64_t offered_ = 0;  // candidate frames offered so far (candidate_index)
  std::string camera_frame_, lidar_frame_;
  bool ids_locked_ = false;
  std::uint64_t tentative_support_ = 0;         // valid frames with the tentative ids
  std::map<FrameIds, std::uint64_t> other_ids_;  // valid frames with other ids, while tentative
  std::uint64_t pairs_dropped_for_ids_ = 0;
  std::uint64_t refused_in_a_row_ = 0;
  FrameIds last_refused_;

  void keep(CalibrationPair pair);
  void finishPending(bool all);
  void measureMotion(CalibrationPair& pair) const;
  std::optional<MotionConfig> motion_;
  std::deque<CalibrationPair> pending_;  // kept, waiting for their later scans
  std::vector<ScanPeople> scans_;        // recent scans, in time order
};

// Kept pairs and candidate frames (as takePairs() and takeCandidates() hand them over) as one
// stream in the order the frames were offered (candidate_index): the drift watch pairs each
// candidate against the pairs before it.
std::vector<CalibrationPair> inOfferOrder(std::vector<CalibrationPair> pairs, std::vector<CalibrationPair> candidates);

}  // namespace thermal_lidar_calibration
