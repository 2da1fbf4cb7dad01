#pragma once
// The drift watch (issue #9): kept pairs go in one by one, in time order; every
// `period_pairs` new pairs the latest `window_pairs` are tested against the extrinsic in use
// (the reference, drift_window_comparison.hpp), and the verdict moves OK / WARN / ERROR
// (drift_state.hpp). Once a change is confirmed the monitor finds where in the window it
// happened and fits the new extrinsic on the pairs since then (the candidate), refitting it as
// pairs come in; it is final once it rests on `update_pairs` pairs (then it is kept: a later
// stretch of pairs with poorer geometry must not undo it).
//
// Accepting the candidate makes it the reference. Accepted before it is final (auto-update at
// the moment of confirmation), the monitor goes on fitting the pairs since the change and
// offers the final one again once it has them (updateReady()), so an early update is followed
// by an accurate one. After an accepted update the tests wait for a window of pairs since the
// change it accepted: older pairs show the old rig. ROS-free; the node and calibrate_bag
// --monitor drive it alike.

#include "thermal_lidar_calibration/core/association_refit.hpp"
#include "thermal_lidar_calibration/core/calibration_config.hpp"
#include "thermal_lidar_calibration/core/calibration_pair.hpp"
#include "thermal_lidar_calibration/core/camera_model.hpp"
#include "thermal_lidar_calibration/core/drift_config.hpp"
#include "thermal_lidar_calibration/core/drift_state.hpp"
#include "thermal_lidar_calibration/core/drift_update_fit.hpp"
#include "thermal_lidar_calibration/core/drift_window_comparison.hpp"
#include "thermal_lidar_calibration/core/extrinsic.hpp"
#include "thermal_lidar_calibration/core/image_offset.hpp"
#include "thermal_lidar_calibration/core/uncertainty.hpp"

#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

namespace thermal_lidar_calibration {

// One window test: a row of the drift timeline.
struct DriftRecord {
  double stamp_s = 0.0;           // the newest pair of the window
  std::uint64_t pairs_seen = 0;   // kept pairs given to the monitor so far
  DriftState state = DriftState::kOk;  // after this test
  DriftWindowTest test;
  // Issue 21: the window changed, but the reference fits it again with the camera's time offset
  // changed by this (drift_timing.hpp): a timing change, not counted as a drift of the extrinsic.
  std::optional<double> timing_change_s;
  DriftState timing_state = DriftState::kOk;  // the timing's own OK / WARN / ERROR
  double seconds = 0.0;           // wall time of this step (test, change point, candidate)
};

// A confirmed new extrinsic and the evidence for it.
struct DriftCandidate {
  Extrinsic extrinsic;
  DriftChange change;             // against the reference in use
  double loss_reference = 0.0;    // Eq. (3), nearest rule, on the candidate's inliers
  double loss_fit = 0.0;
  std::size_t pairs = 0;          // pairs since the estimated change it was fitted on
  std::size_t pairs_used = 0;     // of those, its inliers
  double change_stamp_s = 0.0;    // the first pair after the estimated change
  double stamp_s = 0.0;           // the newest pair it saw
  bool complete = false;          // rests on update_pairs pairs
  // The motion fitted (drift_update_fit.hpp: turn, shift or full pose) and the held-out p-value
  // of the full pose against the simpler model.
  DriftUpdateModel model = DriftUpdateModel::kFull;
  double full_p_value = 1.0;
  double p_value = 1.0;           // of the window test that confirmed the change (changed_p_value)
  // 95 % intervals per axis about the candidate (monitor_update_uncertainty_resamples > 0).
  std::optional<Uncertainty> uncertainty;
  std::optional<double> first_warn_stamp_s, first_error_stamp_s;
};

// An accepted candidate: the history entry of the result file.
struct DriftUpdate {
  Extrinsic old_reference;
  DriftCandidate accepted;
};

class DriftMonitor {
 public:
  // Throws std::invalid_argument on a bad config.
  // `time_offset_s`: the reference's camera time offset (issue 21), when its calibration applied
  // one: pairs are held at their image's instant for it, and a changed window is first asked
  // whether a change of the offset alone explains it.
  DriftMonitor(const CameraModel& camera, const Extrinsic& reference, const DriftConfig& drift,
               const CalibrationConfig& calibration, std::optional<double> time_offset_s = std::nullopt);

  // A kept pair, newer than the previous one (its image is dropped: the monitor needs the mask
  // and points only). Returns the test's record when one ran.
  std::optional<DriftRecord> addPair(CalibrationPair pair);

  // Issue 23: the frames the count rule did not keep (people in both modalities) are paired person
  // by person at the reference in use and its time offset, as the calibration pairs them (H_max;
  // the skip rule counted from the latest pair of either rule), so a watch gets the pairs the
  // calibration got. Off until called: without it the watch pairs by counts alone. Association at
  // the reference cannot hide a change: a frame that no longer lands on its people within the
  // association's tolerance makes no pair, and the pairs it makes are fitted like any other.
  void pairByAssociation(const AssociationPairing& association);
  // A candidate frame (rule kAssociation, `regions` set, newer than the previous pair): its
  // association pair goes in as addPair's would. nullopt when no pair came of it (association
  // off, within the skip rule, nothing matched) or no test ran.
  std::optional<DriftRecord> addCandidate(const CalibrationPair& frame);
  // Either kind in time order: a candidate frame to addCandidate, a kept pair to addPair.
  std::optional<DriftRecord> add(CalibrationPair pair);
  // Of pairsSeen(), those made by association; and the candidate frames offered so far.
  std::uint64_t associationPairs() const { return association_pairs_; }
  std::uint64_t candidatesOffered() const { return candidates_offered_; }

  DriftState state() const { return machine_.state(); }
  DriftState timingState() const { return timing_machine_.state(); }
  std::optional<double> timeOffset() const { return time_offset_s_; }
  // The latest timing change found (s), while the timing state is not OK.
  std::optional<double> timingChange() const { return timing_change_s_; }
  const Extrinsic& reference() const { return reference_; }
  const std::optional<DriftRecord>& lastRecord() const { return last_record_; }
  const std::optional<DriftCandidate>& candidate() const { return candidate_; }
  std::optional<double> firstWarnStamp() const { return machine_.firstWarnStamp(); }
  std::optional<double> firstErrorStamp() const { return machine_.firstErrorStamp(); }
  // A candidate auto-update should take now: a confirmed change (ERROR), or the final fit after
  // an early acceptance.
  bool updateReady() const;
  // Makes the candidate the reference (state OK, a new episode); nullopt if there is none.
  std::optional<DriftUpdate> acceptCandidate();
  // A new reference from elsewhere (a new calibration): forgets the change and the candidate,
  // keeps the pairs.
  void setReference(const Extrinsic& reference);

  // Fits after a confirmed change that were too far from the reference to offer
  // (DriftConfig::max_update_*): the change is there, but not one the watch can refit.
  std::uint64_t candidatesRefused() const { return candidates_refused_; }
  std::uint64_t pairsSeen() const { return next_seq_; }
  std::size_t pairsInWindow() const;  // of the rig in use (since the last accepted change)
  double secondsInTests() const { return seconds_; }  // all steps so far
  const DriftConfig& config() const { return drift_; }

 private:
  struct Held {
    std::uint64_t seq;
    CalibrationPair pair;
    ImageOffset offset;  // against reference_
  };
  std::vector<CalibrationPair> lastPairs(std::size_t n) const;
  // Held pairs since the last accepted change (all of them before any).
  std::size_t pairsSinceAccepted() const;
  // The held pairs' image offsets against reference_, worked out again after it changed.
  void updateOffsets();
  // Held pairs from `seq` on: the latest `at_most` of the count rule's, with the association
  // pairs among them (a new extrinsic rests on update_pairs count-rule pairs: association pairs
  // come faster and from the same stretch of driving, so counted alone they would end the fit on
  // a shorter stretch, with less varied geometry).
  std::vector<CalibrationPair> pairsSince(std::uint64_t seq, std::size_t at_most) const;
  static std::size_t countRulePairs(const std::vector<CalibrationPair>& pairs);
  // After a window's test (`changed`: it counts as an extrinsic change; `before`: the state
  // before it): start over, confirm, place the change and fit the candidate as the state says.
  void followTest(const DriftRecord& record, bool changed, DriftState before);
  // Places the change among the held pairs: where they start fitting `fit` better than the
  // reference (change_point.hpp).
  void locateChange(const Extrinsic& fit);
  void fitCandidate(const Extrinsic& start);
  bool withinUpdateBounds(const DriftChange& change) const;

  CameraModel camera_;
  Extrinsic reference_;
  DriftConfig drift_;
  CalibrationConfig calibration_;
  DriftStateMachine machine_;
  std::optional<double> time_offset_s_;
  DriftStateMachine timing_machine_;
  std::optional<double> timing_change_s_;
  // Issue 21: whether the changed window `test` is a timing change; sets record.timing_change_s.
  bool isTimingChange(const std::vector<CalibrationPair>& window, DriftRecord& record) const;
  std::deque<Held> held_;   // the latest max(window_pairs, update_pairs) count-rule pairs and those among them
  std::uint64_t next_seq_ = 0;
  int since_test_ = 0;
  std::optional<std::uint64_t> change_seq_;  // first pair after the located change
  std::uint64_t accepted_change_seq_ = 0;     // first pair after the last accepted change
  bool settling_ = false;   // accepted early: still fitting the pairs since the change
  std::optional<DriftCandidate> candidate_;
  std::optional<DriftRecord> last_record_;
  double confirm_p_value_ = 1.0;  // of the window test that confirmed the change
  double seconds_ = 0.0;
  std::uint64_t candidates_refused_ = 0;
  std::optional<AssociationPairing> association_;
  std::optional<std::uint64_t> last_index_;  // candidate_index of the latest pair, either rule
  std::uint64_t association_pairs_ = 0;
  std::uint64_t candidates_offered_ = 0;
};

}  // namespace thermal_lidar_calibration
