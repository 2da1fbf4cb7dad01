#include "thermal_lidar_calibration/core/dataset_builder.hpp"

#include "thermal_lidar_calibration/core/person_association.hpp"
#include "thermal_lidar_calibration/core/person_counter.hpp"
#include "thermal_lidar_calibration/core/person_timing.hpp"

#include <algorithm>
#include <exception>
#include <iterator>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace thermal_lidar_calibration {

namespace {

std::string sizeString(int width, int height) {
  return std::to_string(width) + "x" + std::to_string(height);
}

// Throws std::invalid_argument with a one-line, user-actionable reason if the decoded frame
// cannot be used with this camera.
void checkFrame(const Frame& frame, const CameraModel& camera) {
  if (frame.mask.cols != camera.width || frame.mask.rows != camera.height) {
    throw std::invalid_argument(
        "mask is " + sizeString(frame.mask.cols, frame.mask.rows) + " but camera_info says " +
        sizeString(camera.width, camera.height) +
        ": the mask must be the segmentation of the thermal image described by camera_info");
  }
  if (frame.mask.type() != CV_8UC1 && frame.mask.type() != CV_16UC1) {
    throw std::invalid_argument("mask has OpenCV type " + cv::typeToString(frame.mask.type()) +
                                ": expected mono8/8UC1 or mono16/16UC1");
  }
  if (!frame.image.empty()) {
    if (frame.image.cols != frame.mask.cols || frame.image.rows != frame.mask.rows) {
      throw std::invalid_argument(
          "image is " + sizeString(frame.image.cols, frame.image.rows) + " but mask is " +
          sizeString(frame.mask.cols, frame.mask.rows) +
          ": the mask must be the segmentation of that image");
    }
    if (frame.image.type() != CV_8UC1 && frame.image.type() != CV_16UC1) {
      throw std::invalid_argument("thermal image has OpenCV type " +
                                  cv::typeToString(frame.image.type()) +
                                  ": expected mono8/8UC1 or mono16/16UC1");
    }
  }
  if (frame.points.size() != frame.labels.size()) {
    throw std::invalid_argument("clusters have " + std::to_string(frame.points.size()) +
                                " points but " + std::to_string(frame.labels.size()) +
                                " labels: every point needs exactly one label");
  }
  if (!frame.point_time_s.empty() && frame.point_time_s.size() != frame.points.size()) {
    throw std::invalid_argument("clusters have " + std::to_string(frame.points.size()) + " points but " +
                                std::to_string(frame.point_time_s.size()) +
                                " point times: give every point a time or none");
  }
}

}  // namespace

DatasetBuilder::DatasetBuilder(CameraModel camera, GateConfig config, std::optional<MotionConfig> motion)
    : camera_(std::move(camera)), gate_(config), motion_(motion) {
  camera_.validate();
  if (motion_) motion_->validate();
}

OfferOutcome DatasetBuilder::offer(const std::function<Frame()>& decode) {
  return admit(decode, false);
}

OfferOutcome DatasetBuilder::restore(Frame frame, const StoredFrameKind& kind) {
  return admit([&frame] { return std::move(frame); }, true, kind);
}

// The one path for live, bag and stored frames. A stored frame (kept in an earlier session) is
// checked and counted exactly like a live one, but neither the skip rule nor the count rule
// applies again: it was kept under them once, and re-deciding with other settings would
// silently drop work the user has already collected.
OfferOutcome DatasetBuilder::admit(const std::function<Frame()>& decode, bool stored, const StoredFrameKind& kind) {
  OfferOutcome outcome;
  // A stored frame keeps its place in the session that stored it (the skip rule between
  // association pairs counts in it); later frames are numbered after it.
  const std::uint64_t index = stored && kind.frame_index ? *kind.frame_index : offered_;
  offered_ = std::max(offered_, index + 1);
  outcome.frame_index = index;
  if ((!stored && gate_.consumeSkip()) || (stored && kind.skipped)) {
    outcome.decision = GateDecision::kSkipped;
    if (keepsSkippedFrames()) outcome.skipped_held = holdSkippedFrame(decode, index);
    return outcome;
  }

  Frame frame;
  PeopleCounts people;
  try {
    frame = decode();
    checkFrame(frame, camera_);
    checkFrameIds(frame);
    people = countPeople(frame.mask, frame.labels);
    outcome.mask_people = people.mask_people;
    outcome.cluster_people = people.cluster_people;
  } catch (const std::invalid_argument& e) {
    gate_.recordBadMessage();
    outcome.decision = GateDecision::kBadMessage;
    outcome.error = e.what();
    return outcome;
  } catch (const std::exception& e) {
    gate_.recordBadMessage();
    outcome.decision = GateDecision::kBadMessage;
    outcome.error = std::string("could not decode the frame: ") + e.what();
    return outcome;
  }

  gate_.counts().nonfinite_points_dropped += frame.nonfinite_points_dropped;

  if (!stored) {
    outcome.decision = gate_.decide(people.mask_people, people.cluster_people, people.smallest_cluster_points);
  } else if (kind.candidate) {
    outcome.decision = gate_.classify(people.mask_people, people.cluster_people, people.smallest_cluster_points);
  } else {
    outcome.decision = GateDecision::kKept;
  }
  // A frame the count rule did not keep but with people in both modalities may still pair by
  // association (issue 23).
  const bool candidate = outcome.decision != GateDecision::kKept && keep_candidates_ &&
                         people.mask_people > 0 && people.cluster_people > 0;
  outcome.candidate = candidate;
  if (outcome.decision != GateDecision::kKept && !candidate) return outcome;
  hold(std::move(frame), index, candidate ? PairRule::kAssociation : PairRule::kCounts, outcome.mask_people, false);
  return outcome;
}

bool DatasetBuilder::holdSkippedFrame(const std::function<Frame()>& decode, std::uint64_t index) {
  Frame frame;
  PeopleCounts people;
  try {
    frame = decode();
    checkFrame(frame, camera_);
    people = countPeople(frame.mask, frame.labels);
  } catch (const std::exception&) {
    return false;  // counted when a frame the gate decides on is bad the same way
  }
  if (people.mask_people == 0 || people.cluster_people == 0) return false;
  if (frame.camera_frame != camera_frame_ || frame.lidar_frame != lidar_frame_) return false;
  hold(std::move(frame), index, PairRule::kAssociation, people.mask_people, true);
  return true;
}

void DatasetBuilder::hold(Frame frame, std::uint64_t index, PairRule rule, int people, bool skipped) {
  CalibrationPair pair;
  pair.stamp_s = frame.stamp_s;
  pair.candidate_index = index;
  pair.rule = rule;
  pair.outside_skip_rule = skipped;
  if (rule == PairRule::kAssociation) {
    pair.regions = personRegions(frame.mask);  // the mask itself follows once a pair is made
  } else {
    pair.mask = binarizeMask(frame.mask);
  }
  // A decoder may wrap a message buffer (cv_bridge::toCvShare): keep a copy we own. A skipped
  // frame holds none: its neighbours show the same scene, and the skipped ones would double
  // what the held frames take (the report draws the pairs that have one).
  if (!skipped) pair.image = frame.image.u != nullptr ? frame.image : frame.image.clone();
  pair.points = std::move(frame.points);
  pair.labels = std::move(frame.labels);
  pair.people = people;
  pair.cloud_stamp_s = frame.cloud_stamp_s;
  pair.point_time_s = std::move(frame.point_time_s);
  pair.point_velocity = std::move(frame.point_velocity);
  if (!pair.point_velocity.empty()) pair.motion = std::move(frame.motion);
  if (motion_ && pair.point_velocity.empty()) {
    pending_.push_back(std::move(pair));
    finishPending(false);
  } else {
    keep(std::move(pair));
  }
}

void DatasetBuilder::keepAssociationCandidates(bool keep, std::size_t max_candidates) {
  if (max_candidates == 0) throw std::invalid_argument("association candidates: the bound must be at least 1");
  keep_candidates_ = keep;
  max_candidates_ = max_candidates;
}

// Frames seen so far are numbered 0, 1, 2, ...; those held are the multiples of the stride.
// Full: the odd multiples go and the stride doubles, so the held ones stay evenly spaced.
std::uint64_t DatasetBuilder::SpacedFrames::add(CalibrationPair pair, std::size_t bound) {
  if (seen++ % stride != 0) return 1;
  held.push_back(std::move(pair));
  if (held.size() <= bound) return 0;
  std::size_t kept = 0;
  for (std::size_t i = 0; i < held.size(); i += 2) held[kept++] = std::move(held[i]);
  const std::uint64_t dropped = held.size() - kept;
  held.resize(kept);
  stride *= 2;
  return dropped;
}

std::vector<CalibrationPair> DatasetBuilder::SpacedFrames::take() {
  std::vector<CalibrationPair> out;
  out.swap(held);
  seen = 0;
  stride = 1;
  return out;
}

void DatasetBuilder::keep(CalibrationPair pair) {
  if (pair.outside_skip_rule) {
    skipped_.add(std::move(pair), max_candidates_);  // extra frames: their drops are not the candidates'
    return;
  }
  if (pair.rule == PairRule::kAssociation) {
    candidates_dropped_ += candidates_.add(std::move(pair), max_candidates_);
    return;
  }
  pairs_.push_back(std::move(pair));
  if (pairs_.size() >= kLockPairs) {
    ids_locked_ = true;
    other_ids_.clear();
  }
}

void DatasetBuilder::observeScan(ScanPeople scan) {
  if (!motion_) return;
  const auto later = std::upper_bound(scans_.begin(), scans_.end(), scan.stamp_s,
                                      [](double t, const ScanPeople& s) { return t < s.stamp_s; });
  if (later != scans_.begin() && std::prev(later)->stamp_s == scan.stamp_s) return;  // seen
  scans_.insert(later, std::move(scan));
  finishPending(false);
  // Keep what a waiting pair or the next one can still need: the window before the oldest
  // waiting pair (or the newest scan), with room for holes.
  const double keep_from = (pending_.empty() ? scans_.back().stamp_s : pending_.front().cloud_stamp_s) -
                           (motion_->window_scans + 1) * motion_->max_gap_s;
  std::size_t drop = 0;
  while (drop < scans_.size() && scans_[drop].stamp_s < keep_from) ++drop;
  scans_.erase(scans_.begin(), scans_.begin() + static_cast<std::ptrdiff_t>(drop));
}

// A waiting pair is ready when window_scans scans after its own have arrived, or when the scans
// have moved on so far that none still to come could be used.
void DatasetBuilder::finishPending(bool all) {
  while (!pending_.empty()) {
    CalibrationPair& pair = pending_.front();
    if (!all) {
      int after = 0;
      for (auto it = scans_.rbegin(); it != scans_.rend() && it->stamp_s > pair.cloud_stamp_s; ++it) ++after;
      const double newest = scans_.empty() ? pair.cloud_stamp_s : scans_.back().stamp_s;
      const bool waited_enough = newest - pair.cloud_stamp_s > motion_->window_scans * motion_->max_gap_s;
      if (after < motion_->window_scans && !waited_enough) return;
    }
    measureMotion(pair);
    keep(std::move(pair));
    pending_.pop_front();
  }
}

void DatasetBuilder::measureMotion(CalibrationPair& pair) const {
  // Its own scan, as observed; a pair whose scan was never observed on its own brings it along.
  std::vector<ScanPeople> scans = scans_;
  auto own = std::find_if(scans.begin(), scans.end(),
                          [&](const ScanPeople& s) { return s.stamp_s == pair.cloud_stamp_s; });
  if (own == scans.end()) {
    const auto later = std::upper_bound(scans.begin(), scans.end(), pair.cloud_stamp_s,
                                        [](double t, const ScanPeople& s) { return t < s.stamp_s; });
    own = scans.insert(later, summariseScan(pair.cloud_stamp_s, pair.points, pair.labels, pair.point_time_s));
  }
  attachMotion(pair, estimateMotion(scans, static_cast<std::size_t>(own - scans.begin()), *motion_));
}

void DatasetBuilder::flushPending() {
  if (motion_) finishPending(true);
}

std::vector<PersonMotion> DatasetBuilder::latestMotion() const {
  if (!motion_ || scans_.empty()) return {};
  return estimateMotion(scans_, scans_.size() - 1, *motion_);
}

void DatasetBuilder::checkFrameIds(const Frame& frame) {
  const bool have_ids = tentative_support_ > 0 || ids_locked_;
  if (!have_ids || (frame.camera_frame == camera_frame_ && frame.lidar_frame == lidar_frame_)) {
    if (!have_ids) {
      camera_frame_ = frame.camera_frame;
      lidar_frame_ = frame.lidar_frame;
    }
    if (!ids_locked_) ++tentative_support_;
    refused_in_a_row_ = 0;
    return;
  }
  const FrameIds ids(frame.camera_frame, frame.lidar_frame);
  if (!ids_locked_) {
    std::uint64_t& support = other_ids_[ids];
    if (++support > tentative_support_) {
      // These ids have been seen in more valid frames than the tentative ones: the tentative
      // ids came from a few stray frames. Their pairs (fewer than kLockPairs) go.
      for (const CalibrationPair& p : pending_) pairs_dropped_for_ids_ += p.rule == PairRule::kCounts ? 1 : 0;
      pairs_dropped_for_ids_ += pairs_.size();
      pairs_.clear();
      candidates_.take();
      skipped_.take();
      pending_.clear();
      camera_frame_ = ids.first;
      lidar_frame_ = ids.second;
      tentative_support_ = support;
      other_ids_.clear();
      refused_in_a_row_ = 0;
      return;
    }
  }
  ++refused_in_a_row_;
  last_refused_ = ids;
  throw std::invalid_argument("frame ids changed: camera '" + frame.camera_frame + "', lidar '" +
                              frame.lidar_frame + "' but the dataset's pairs use '" +
                              camera_frame_ + "', '" + lidar_frame_ +
                              "': all frames must come from the same two sensors");
}

std::optional<FrameIdConflict> DatasetBuilder::frameIdConflict(std::uint64_t min_in_a_row) const {
  if (!ids_locked_ || refused_in_a_row_ < min_in_a_row) return std::nullopt;
  return FrameIdConflict{camera_frame_, lidar_frame_, last_refused_.first, last_refused_.second,
                         refused_in_a_row_};
}

std::vector<CalibrationPair> DatasetBuilder::takeCandidates() { return candidates_.take(); }

std::vector<CalibrationPair> DatasetBuilder::takeSkippedFrames() { return skipped_.take(); }

std::vector<CalibrationPair> DatasetBuilder::takePairs() {
  std::vector<CalibrationPair> out;
  out.swap(pairs_);
  return out;
}

void DatasetBuilder::reset() {
  pairs_.clear();
  candidates_.take();
  skipped_.take();
  candidates_dropped_ = 0;
  offered_ = 0;
  pending_.clear();
  scans_.clear();
  gate_.reset();
  camera_frame_.clear();
  lidar_frame_.clear();
  ids_locked_ = false;
  tentative_support_ = 0;
  other_ids_.clear();
  pairs_dropped_for_ids_ = 0;
  refused_in_a_row_ = 0;
}

std::vector<CalibrationPair> inOfferOrder(std::vector<CalibrationPair> pairs, std::vector<CalibrationPair> candidates) {
  std::vector<CalibrationPair> out;
  out.reserve(pairs.size() + candidates.size());
  std::merge(std::make_move_iterator(pairs.begin()), std::make_move_iterator(pairs.end()),
             std::make_move_iterator(candidates.begin()), std::make_move_iterator(candidates.end()),
             std::back_inserter(out), [](const CalibrationPair& a, const CalibrationPair& b) {
               return a.candidate_index < b.candidate_index;
             });
  return out;
}

}  // namespace thermal_lidar_calibration
