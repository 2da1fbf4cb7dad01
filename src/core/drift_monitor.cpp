#include "thermal_lidar_calibration/core/drift_monitor.hpp"

#include "thermal_lidar_calibration/core/change_point.hpp"
#include "thermal_lidar_calibration/core/distance_map.hpp"
#include "thermal_lidar_calibration/core/drift_timing.hpp"
#include "thermal_lidar_calibration/core/timing_resolution.hpp"
#include "thermal_lidar_calibration/core/drift_update_fit.hpp"
#include "thermal_lidar_calibration/core/local_fit.hpp"
#include "thermal_lidar_calibration/core/loss.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>

namespace thermal_lidar_calibration {

DriftMonitor::DriftMonitor(const CameraModel& camera, const Extrinsic& reference,
                           const DriftConfig& drift, const CalibrationConfig& calibration,
                           std::optional<double> time_offset_s)
    : camera_(camera),
      reference_(reference),
      drift_(drift),
      calibration_(calibration),
      machine_(drift.confirm_windows),
      time_offset_s_(time_offset_s),
      timing_machine_(drift.confirm_windows) {
  camera_.validate();
  drift_.validate();
  calibration_.validate();
}

bool DriftMonitor::withinUpdateBounds(const DriftChange& change) const {
  return change.angle_deg <= drift_.max_update_rotation_deg &&
         change.distance_cm <= drift_.max_update_translation_cm;
}

std::size_t DriftMonitor::pairsInWindow() const {
  return std::min(pairsSinceAccepted(), static_cast<std::size_t>(drift_.window_pairs));
}

std::size_t DriftMonitor::pairsSinceAccepted() const {
  std::size_t n = 0;
  for (const Held& h : held_) n += h.seq >= accepted_change_seq_ ? 1 : 0;
  return n;
}

std::vector<CalibrationPair> DriftMonitor::lastPairs(std::size_t n) const {
  std::vector<CalibrationPair> out;
  const std::size_t first = held_.size() - std::min(n, held_.size());
  for (std::size_t i = first; i < held_.size(); ++i) out.push_back(held_[i].pair);
  return out;
}

namespace {
bool byCounts(const CalibrationPair& p) { return p.rule == PairRule::kCounts; }
}  // namespace

std::vector<CalibrationPair> DriftMonitor::pairsSince(std::uint64_t seq,
                                                      std::size_t at_most) const {
  std::vector<CalibrationPair> out;
  for (const Held& h : held_) {
    if (h.seq >= seq) out.push_back(h.pair);
  }
  // The latest `at_most` of the count rule's pairs, with the association pairs among them.
  std::size_t counts = countRulePairs(out);
  auto first = out.begin();
  while (first != out.end() && (counts > at_most || (counts == at_most && !byCounts(*first)))) {
    counts -= byCounts(*first) ? 1 : 0;
    ++first;
  }
  out.erase(out.begin(), first);
  return out;
}

std::size_t DriftMonitor::countRulePairs(const std::vector<CalibrationPair>& pairs) {
  return static_cast<std::size_t>(std::count_if(pairs.begin(), pairs.end(), byCounts));
}

void DriftMonitor::updateOffsets() {
  if (held_.empty()) return;
  const auto started = std::chrono::steady_clock::now();
  const LossEvaluator bilinear(
      camera_, lastPairs(held_.size()),
      LossConfig{calibration_.behind_camera_penalty_c1, PixelRule::kBilinear});
  for (std::size_t i = 0; i < held_.size(); ++i) {
    held_[i].offset = pairImageOffset(bilinear, i, reference_, {}, calibration_.num_threads);
  }
  seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
}

bool DriftMonitor::isTimingChange(const std::vector<CalibrationPair>& window, DriftRecord& record) const {
  if (!time_offset_s_) return false;
  const std::optional<TimingChangeFit> t =
      fitTimingChange(camera_, window, reference_, record.test.fit, calibration_.time_offset.max_s,
                      calibration_.behind_camera_penalty_c1, calibration_.outlier.threshold_px);
  if (!t || std::abs(t->change_s) * 1000.0 < drift_.min_timing_change_ms ||
      !t->interior(calibration_.time_offset.max_s)) {
    return false;
  }
  // Only a window whose motion tells the offset from the pose can blame timing: on straight
  // steady driving past standing people a latency change and a shift along the travel are the
  // same data (the CLI's bump drive read a 3 cm shift as -114 ms). The change must stand three
  // of the window's 1-sigma resolutions clear of zero (the window's pairs are already at the
  // reference's offset).
  std::vector<std::size_t> all(window.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  const TimingResolution resolution = timingResolution(camera_, window, all, reference_, 0.0);
  if (!(std::abs(t->change_s) * 1000.0 >= 3.0 * resolution.resolution_ms)) return false;
  // A window the pose test calls changed is timing only if the offset explains most of what the
  // pose fit gains. When people move at different speeds a latency change is no pose change at
  // all (the pose test sees nothing while the loss grows): then the offset alone must make the
  // reference fit as much better as the pose test asks of a change (monitor_min_loss_ratio).
  if (record.test.changed() ? t->explained() < drift_.timing_explained_fraction
                            : t->loss * drift_.min_loss_ratio > t->loss_reference) {
    return false;
  }
  record.timing_change_s = t->change_s;
  return true;
}

void DriftMonitor::pairByAssociation(const AssociationPairing& association) {
  association.config.validate();
  association_ = association;
}

std::optional<DriftRecord> DriftMonitor::add(CalibrationPair pair) {
  if (pair.rule == PairRule::kAssociation && pair.mask.empty()) return addCandidate(pair);
  return addPair(std::move(pair));
}

std::optional<DriftRecord> DriftMonitor::addCandidate(const CalibrationPair& frame) {
  ++candidates_offered_;
  if (!association_) return std::nullopt;
  const auto skip = static_cast<std::uint64_t>(association_->limits.skip_frames);
  if (last_index_ && frame.candidate_index <= *last_index_ + skip) return std::nullopt;
  std::optional<CalibrationPair> pair =
      associateCandidate(camera_, frame, reference_, time_offset_s_, association_->config, association_->limits);
  if (!pair) return std::nullopt;
  ++association_pairs_;
  return addPair(std::move(*pair));
}

std::optional<DriftRecord> DriftMonitor::addPair(CalibrationPair pair) {
  pair.image.release();
  last_index_ = last_index_ ? std::max(*last_index_, pair.candidate_index) : pair.candidate_index;
  // Held at the image's instant for the reference's time offset (issue 21).
  if (time_offset_s_) pair = rebasedAtTimeOffset(std::move(pair), *time_offset_s_);
  // Its mask's distance map, once: every window that holds the pair builds evaluators over it
  // (the window test, the timing check, the update's fit), which built the map again each time.
  if (!pair.distance_map) pair.distance_map = sharedDistanceMap(pair.mask);
  // The watch's own time for this pair, whichever way it returns (seconds()).
  const auto started = std::chrono::steady_clock::now();
  auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  };
  // Its image offset against the reference, once (the tests of the next windows share it).
  const LossEvaluator bilinear(
      camera_, {pair}, LossConfig{calibration_.behind_camera_penalty_c1, PixelRule::kBilinear});
  const ImageOffset offset = pairImageOffset(bilinear, 0, reference_, {}, calibration_.num_threads);
  held_.push_back({next_seq_++, std::move(pair), offset});
  // Enough for a window and for a new extrinsic on update_pairs count-rule pairs with the
  // association pairs among them (at most 4x that in all, should the count rule keep nothing).
  const std::size_t keep =
      static_cast<std::size_t>(std::max(drift_.window_pairs, drift_.update_pairs));
  std::size_t counts_held = 0;
  for (const Held& h : held_) counts_held += byCounts(h.pair) ? 1 : 0;
  while (held_.size() > keep) {
    const std::size_t counts_after = counts_held - (byCounts(held_.front().pair) ? 1 : 0);
    if (counts_after < keep && held_.size() <= 4 * keep) break;
    counts_held = counts_after;
    held_.pop_front();
  }
  ++since_test_;
  // A window holds only pairs of the rig in use: after an accepted update none from before the
  // change it accepted (they show the old rig, and against the new reference they look like a
  // change of their own).
  const bool window_ready = pairsSinceAccepted() >= static_cast<std::size_t>(drift_.window_pairs);
  if (since_test_ < drift_.period_pairs || (!window_ready && !settling_)) {
    seconds_ += elapsed();
    return std::nullopt;
  }
  since_test_ = 0;
  if (!window_ready) {
    // Accepted early, no window of the new rig yet: go on refitting the final candidate.
    if (!(candidate_ && candidate_->complete)) fitCandidate(reference_);
    seconds_ += elapsed();
    return std::nullopt;
  }

  const std::vector<CalibrationPair> window = lastPairs(drift_.window_pairs);
  std::vector<ImageOffset> offsets;
  for (std::size_t i = held_.size() - window.size(); i < held_.size(); ++i) {
    offsets.push_back(held_[i].offset);
  }
  DriftRecord record;
  record.stamp_s = window.back().stamp_s;
  record.pairs_seen = next_seq_;
  record.test = testDriftWindow(camera_, window, reference_, drift_, calibration_, offsets);
  // A change the camera's time offset explains is timing, kept apart from the extrinsic's state.
  const bool timing = isTimingChange(window, record);
  record.timing_state = timing_machine_.onTest(timing, record.stamp_s);
  timing_change_s_ = record.timing_state == DriftState::kOk ? std::nullopt
                     : timing                              ? record.timing_change_s
                                                           : timing_change_s_;
  const bool changed = record.test.changed() && !timing;
  const DriftState before = machine_.state();
  record.state = machine_.onTest(changed, record.stamp_s);

  followTest(record, changed, before);

  record.seconds = elapsed();
  seconds_ += record.seconds;
  last_record_ = record;
  return record;
}

void DriftMonitor::followTest(const DriftRecord& record, bool changed, DriftState before) {
  if (changed) {
    if (settling_) {
      // A change against the early update: start over from this window.
      settling_ = false;
      change_seq_.reset();
      candidate_.reset();
    }
    if (record.state == DriftState::kError && before != DriftState::kError) {
      confirm_p_value_ = record.test.changed_p_value;
    }
  } else if (record.state == DriftState::kOk && !settling_) {
    change_seq_.reset();  // the suspicion did not hold
  }
  const bool candidate_final = candidate_ && candidate_->complete;
  if (record.state == DriftState::kError && !candidate_final) {
    // Place the change with the best pose for "after" there is (the candidate once there is
    // one, more pairs make it sharper), fit the pairs since then, and place it again with that
    // fit: a split placed too early hands the fit old pairs, which pull it back.
    const Extrinsic after = candidate_                                ? candidate_->extrinsic
                            : withinUpdateBounds(record.test.change) ? record.test.fit
                                                                      : reference_;
    locateChange(after);
    fitCandidate(after);
    const std::optional<std::uint64_t> placed = change_seq_;
    locateChange(candidate_ ? candidate_->extrinsic : after);
    if (change_seq_ != placed) fitCandidate(candidate_ ? candidate_->extrinsic : after);
  } else if (changed && record.state != DriftState::kError) {
    locateChange(record.test.fit);
  } else if (settling_ && !candidate_final) {
    fitCandidate(reference_);
  }
}

void DriftMonitor::locateChange(const Extrinsic& fit) {
  // Only pairs since the last accepted change: older ones show a rig that is gone. They can
  // fit the new pose too (a bracket that seats back), and a split among them would hand the
  // new fit the pairs of the rig in between.
  const std::size_t since_accepted = pairsSinceAccepted();
  if (since_accepted == 0) return;
  const std::vector<CalibrationPair> held = lastPairs(since_accepted);
  const LossEvaluator bilinear(
      camera_, held,
      LossConfig{calibration_.behind_camera_penalty_c1, PixelRule::kBilinear});
  const double threshold = calibration_.outlier.threshold_px;
  std::vector<double> differences;
  for (std::size_t i = 0; i < held.size(); ++i) {
    const double at_reference = bilinear.pairLoss(i, reference_);
    const double at_fit = bilinear.pairLoss(i, fit);
    // A pair neither explains (mismatched people) says nothing about when the change came.
    differences.push_back(std::min(at_reference, at_fit) > threshold ? 0.0
                                                                      : at_reference - at_fit);
  }
  // At least 6 pairs after the change: the candidate has six parameters to fit on them.
  constexpr std::size_t min_after = 6;
  const std::size_t k = signChangePoint(differences, min_after);
  change_seq_ = held_[held_.size() - held.size() + k].seq;
}

void DriftMonitor::fitCandidate(const Extrinsic& start) {
  if (!change_seq_) return;
  const std::vector<CalibrationPair> pairs =
      pairsSince(*change_seq_, static_cast<std::size_t>(drift_.update_pairs));
  if (pairs.size() < std::max<std::size_t>(6, 2 * static_cast<std::size_t>(drift_.folds))) return;
  const LossEvaluator nearest(
      camera_, pairs, LossConfig{calibration_.behind_camera_penalty_c1, PixelRule::kNearest});
  const DriftUpdateFit update = fitDriftUpdate(nearest, reference_, start, drift_, calibration_);
  const LocalFit& fit = update.fit;
  DriftCandidate c;
  c.model = update.model;
  c.full_p_value = update.full_p_value;
  c.extrinsic = fit.estimate;
  c.change = driftChange(fit.estimate, reference_);
  if (!withinUpdateBounds(c.change)) {
    candidate_.reset();  // the next test starts again from its window's fit
    ++candidates_refused_;
    return;
  }
  c.loss_reference = nearest.loss(reference_, fit.used);
  c.loss_fit = nearest.loss(fit.estimate, fit.used);
  c.pairs = pairs.size();
  c.pairs_used = fit.used.size();
  c.change_stamp_s = pairs.front().stamp_s;
  for (const Held& h : held_) {
    if (h.seq == *change_seq_) c.change_stamp_s = h.pair.stamp_s;
  }
  c.stamp_s = pairs.back().stamp_s;
  c.complete = countRulePairs(pairs) >= static_cast<std::size_t>(drift_.update_pairs);
  c.p_value = confirm_p_value_;
  c.first_warn_stamp_s = machine_.firstWarnStamp();
  c.first_error_stamp_s = machine_.firstErrorStamp();
  if (drift_.update_uncertainty_resamples > 0 && fit.used.size() >= 3) {
    UncertaintyConfig u = UncertaintyConfig::quick();
    u.resamples = drift_.update_uncertainty_resamples;
    u.seed = calibration_.seed;
    u.num_threads = calibration_.num_threads;
    c.uncertainty = estimateUncertainty(nearest, fit.estimate, fit.used, u);
  }
  candidate_ = c;
}

bool DriftMonitor::updateReady() const {
  if (!candidate_) return false;
  return machine_.state() == DriftState::kError || (settling_ && candidate_->complete);
}

std::optional<DriftUpdate> DriftMonitor::acceptCandidate() {
  if (!candidate_) return std::nullopt;
  DriftUpdate update{reference_, *candidate_};
  reference_ = candidate_->extrinsic;
  if (change_seq_) accepted_change_seq_ = *change_seq_;
  settling_ = !candidate_->complete;
  if (!settling_) change_seq_.reset();
  candidate_.reset();
  machine_.reset();
  updateOffsets();
  return update;
}

void DriftMonitor::setReference(const Extrinsic& reference) {
  reference_ = reference;
  machine_.reset();
  change_seq_.reset();
  settling_ = false;
  candidate_.reset();
  updateOffsets();
}

}  // namespace thermal_lidar_calibration
