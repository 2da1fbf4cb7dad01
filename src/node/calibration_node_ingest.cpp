// calibration_node: intrinsics, the synchronized frames through the shared ingest path
// (FrameSynchronizer -> DatasetBuilder), the dataset bag and ~resume.

#include "thermal_lidar_calibration/node/calibration_node.hpp"

#include "thermal_lidar_calibration/core/coverage.hpp"
#include "thermal_lidar_calibration/core/person_timing.hpp"
#include "thermal_lidar_calibration/core/verdict.hpp"
#include "thermal_lidar_calibration/ros/msg_conversion.hpp"
#include "thermal_lidar_calibration/ros/velocity_fields.hpp"

#include <unistd.h>

#include <stdexcept>

namespace thermal_lidar_calibration {
namespace ros_io {

void CalibrationNode::resumeDataset() {
  if (::access(params_.dataset_bag.c_str(), F_OK) != 0) {
    ROS_INFO("~resume: %s does not exist yet; starting a new dataset", params_.dataset_bag.c_str());
    return;
  }
  if (recoverDatasetBag(params_.dataset_bag)) {
    ROS_WARN("~resume: %s was interrupted during a write; restored it from its journal",
             params_.dataset_bag.c_str());
  }
  DatasetBagContents contents = readDatasetBag(params_.dataset_bag);  // throws runtime_error
  if (!builder_) {
    if (!contents.camera) {
      throw std::runtime_error("~resume: " + params_.dataset_bag +
                               " holds no camera_info; set ~camera_info_file");
    }
    camera_info_msg_ = cameraInfoFromModel(*contents.camera);
    createBuilder(*contents.camera, params_.dataset_bag);
  }
  const std::string camera_frame = contents.camera_frame, lidar_frame = contents.lidar_frame;
  const RestoredDataset restored = restoreDataset(std::move(contents), *builder_);
  for (const auto& error : restored.skipped) ROS_WARN("~resume: skipped a stored frame: %s", error.c_str());
  // The exact header stamps, as onFrame keys live frames (not ros::Time(pair.stamp_s): a double
  // at epoch times has ~240 ns resolution, so the nanoseconds would not round-trip).
  for (const std::uint64_t ns : restored.stamps_ns) stored_stamps_ns_.insert(static_cast<long long>(ns));
  pairs_resumed_ = builder_->pairs().size();
  finished_pairs_ = pairs_resumed_;  // already in the bag
  std::vector<StoredPairStamp> stored;
  for (const CalibrationPair& pair : builder_->pairs()) {
    stored.push_back({pair.stamp_s, restored.numbered ? std::optional<std::uint64_t>(pair.candidate_index) : std::nullopt});
  }
  stored_spacing_.emplace(std::move(stored), params_.core.gate.skip_frames);
  if (!builder_->candidates().empty()) last_candidate_recorded_ = builder_->candidates().back().candidate_index;
  if (!builder_->skippedFrames().empty()) last_skipped_recorded_ = builder_->skippedFrames().back().candidate_index;
  camera_frame_ = camera_frame;
  lidar_frame_ = lidar_frame;
  std::string candidates =
      builder_->candidates().empty() ? "" : " and " + std::to_string(builder_->candidates().size()) + " association candidates";
  if (!builder_->skippedFrames().empty()) {
    candidates += " and " + std::to_string(builder_->skippedFrames().size()) + " skipped frames";
  }
  ROS_INFO("~resume: reloaded %zu pairs%s from %s", pairs_resumed_, candidates.c_str(), params_.dataset_bag.c_str());
}

void CalibrationNode::onCameraInfo(const sensor_msgs::CameraInfo::ConstPtr& msg) {
  if (builder_) return;  // intrinsics are cached from the first valid message
  guard_.run(camera_info_topic_, [&] {
    try {
      const CameraModel camera = cameraModelFromMsg(*msg);
      camera_info_msg_ = *msg;
      createBuilder(camera, camera_info_topic_);
      camera_info_sub_.shutdown();
    } catch (const std::invalid_argument& e) {
      ROS_WARN_THROTTLE(5.0, "%s: %s", camera_info_topic_.c_str(), e.what());
    }
  });
}

// Every input message: its topic's rate, and the data time from which the tf check waits.
void CalibrationNode::noteInput(std::size_t topic) {
  input_rates_->message(topic, InputRates::Clock::now());
  if (!first_input_time_ && !ros::Time::now().isZero()) first_input_time_ = ros::Time::now();
}

// Input callbacks: the synchronizer refuses stamps ApproximateTime cannot handle (named in a
// throttled warning); anything else that throws is caught by the guard, never ends the node.
void CalibrationNode::onImage(const sensor_msgs::Image::ConstPtr& msg) {
  guard_.run(image_topic_, [&] {
    noteInput(0);
    reportSyncFault(image_topic_, synchronizer_->addImage(msg));
    overlay_->onImage(msg);
  });
}

void CalibrationNode::onMask(const sensor_msgs::Image::ConstPtr& msg) {
  guard_.run(mask_topic_, [&] {
    noteInput(1);
    reportSyncFault(mask_topic_, synchronizer_->addMask(msg));
    overlay_->onMask(msg);
  });
}

void CalibrationNode::onClusters(const sensor_msgs::PointCloud2::ConstPtr& msg) {
  guard_.run(clusters_topic_, [&] {
    noteInput(2);
    reportSyncFault(clusters_topic_, synchronizer_->addClusters(msg));
    overlay_->onClusters(msg);
    observeScan(*msg);
  });
}

// Every clusters message, kept frame or not, is a scan the people's motion is measured from
// (issue 21); it may finish kept pairs that waited for it. One that cannot be decoded is
// reported when its frame is.
void CalibrationNode::observeScan(const sensor_msgs::PointCloud2& clusters) {
  if (!builder_ || !builder_->tracksMotion()) return;
  try {
    builder_->observeScan(decodeScanPeople(clusters, clusters_topic_, PointTimeField::parse(params_.core.point_time_field)));
  } catch (const std::invalid_argument&) {
    return;
  }
  last_scan_time_ = ros::WallTime::now();
  overlay_->setMotion(builder_->latestMotion(), builder_->latestScanStamp());
  handleFinishedPairs();
}

// Kept pairs that have their people's motion: into the dataset bag (with it), then the fit
// or the drift watch.
void CalibrationNode::handleFinishedPairs() {
  if (state_ == CalibrationStatus::MONITORING) {
    monitorKeptPairs();
    return;
  }
  bool added = false;
  while (finished_pairs_ < builder_->pairs().size()) {
    const CalibrationPair& pair = builder_->pairs()[finished_pairs_++];
    added = true;
    if (kept_messages_.empty()) continue;  // a pair from ~resume: already in the bag
    KeptMessages kept = std::move(kept_messages_.front());
    kept_messages_.pop_front();
    if (kept.image->header.stamp.toSec() != pair.stamp_s) {
      ROS_ERROR("internal: the kept pair at %.3f does not match its messages at %.3f; not recorded", pair.stamp_s,
                kept.image->header.stamp.toSec());
      continue;
    }
    record(kept, pair, StoredFrameKind{false, pair.candidate_index});
  }
  recordHeldCandidates();
  if (!added) return;
  assessCollection();
  if (builder_->pairs().size() >= nextFitPairs() && state_ == CalibrationStatus::COLLECTING) {
    startOptimization(next_fit_pairs_ == 0 ? "~pairs_required reached"
                                           : "~stop_when quality: " + std::to_string(nextFitPairs()) +
                                                 " pairs, fitting again");
  }
}

// One finished frame into the dataset bag, with its people's motion when measured.
void CalibrationNode::record(const KeptMessages& kept, const CalibrationPair& pair, const StoredFrameKind& kind) {
  const bool was_recording = recorder_->recording();
  recorder_->record(*kept.image, *kept.mask,
                    hasMeasuredMotion(pair) ? withVelocityFields(*kept.clusters, pair.motion, clusters_topic_)
                                            : *kept.clusters,
                    *camera_info_msg_, kind);
  if (was_recording && !recorder_->recording()) {  // this write failed: say so everywhere now
    state_message_ = "recording stopped: " + recorder_->stopReason();
    publishStatus();
    diagnostics_->publishNow();
  }
}

// Candidates and skipped frames the builder now holds that are not in the bag yet (newer than
// the last recorded: the builder holds each kind in frame order and only ever drops some).
// Their messages wait in candidate_messages_ until their frame is finished; frames at or before
// the newest finished one are done with, held or passed over by the bound.
void CalibrationNode::recordHeldCandidates() {
  if (candidate_messages_.empty()) return;
  std::optional<std::uint64_t> newest_finished;
  if (!builder_->pairs().empty()) newest_finished = builder_->pairs().back().candidate_index;
  const auto recordNew = [&](const std::vector<CalibrationPair>& held, std::optional<std::uint64_t>& last,
                             bool skipped) {
    for (const CalibrationPair& frame : held) {
      if (last && frame.candidate_index <= *last) continue;
      last = frame.candidate_index;
      const auto messages = candidate_messages_.find(frame.candidate_index);
      if (messages == candidate_messages_.end()) continue;
      stored_stamps_ns_.insert(static_cast<long long>(messages->second.image->header.stamp.toNSec()));
      record(messages->second, frame, StoredFrameKind{true, frame.candidate_index, skipped});
    }
    if (last) newest_finished = std::max(newest_finished.value_or(0), *last);
  };
  recordNew(builder_->candidates(), last_candidate_recorded_, false);
  recordNew(builder_->skippedFrames(), last_skipped_recorded_, true);
  if (!newest_finished) return;
  // Frames still waiting for their motion are newer than every finished one.
  candidate_messages_.erase(candidate_messages_.begin(), candidate_messages_.upper_bound(*newest_finished));
}

// The end of a replay, or a sensor that stopped: pairs still waiting for later scans get the
// motion the scans there are show, rather than never joining the dataset.
void CalibrationNode::finishWaitingPairs() {
  if (!builder_ || builder_->pendingPairs() == 0) return;
  if ((ros::WallTime::now() - last_scan_time_).toSec() < kScanSilenceS) return;
  builder_->flushPending();
  handleFinishedPairs();
}

void CalibrationNode::reportSyncFault(const std::string& topic,
                                      const FrameSynchronizer::AddOutcome& outcome) {
  if (outcome.fault.empty()) return;
  if (const auto held_back = fault_throttle_.admit(topic + ": " + outcome.fault)) {
    ROS_WARN("%s: %s (%llu messages refused for their stamps so far)%s", topic.c_str(),
             outcome.fault.c_str(), static_cast<unsigned long long>(synchronizer_->droppedStamps()),
             fault_throttle_.heldBackText(*held_back).c_str());
  }
}

std::string frameIdConflictText(const FrameIdConflict& c, std::size_t pairs) {
  return std::to_string(c.frames_in_a_row) + " frames in a row have camera '" +
         c.other_camera_frame + "', lidar '" + c.other_lidar_frame + "' but the " +
         std::to_string(pairs) + " pairs kept are of camera '" + c.camera_frame + "', lidar '" +
         c.lidar_frame + "': if the new ids are the sensors to calibrate, call ~reset (drops those " +
         "pairs); otherwise remap the inputs so that one camera and one LiDAR reach the node";
}

// Frames that keep disagreeing with the dataset's frame ids are an error on ~status,
// /diagnostics and the log: the node would otherwise sit at "collecting" and never finish.
void CalibrationNode::reportFrameIdConflict() {
  const auto conflict = builder_->frameIdConflict();
  if (!conflict) {
    if (frame_id_conflict_) {
      frame_id_conflict_ = false;
      setState(state_, "collecting again: frames with the dataset's frame ids arrive");
    }
    return;
  }
  const std::string text = frameIdConflictText(*conflict, builder_->pairs().size());
  if (const auto held_back = fault_throttle_.admit("frame id conflict")) {
    ROS_ERROR("%s%s", text.c_str(), fault_throttle_.heldBackText(*held_back).c_str());
  }
  if (!frame_id_conflict_) {
    frame_id_conflict_ = true;
    setState(state_, "error: " + text);
    diagnostics_->publishNow();
  }
}

void CalibrationNode::onFrame(const sensor_msgs::Image::ConstPtr& image,
                              const sensor_msgs::Image::ConstPtr& mask,
                              const sensor_msgs::PointCloud2::ConstPtr& clusters) {
  input_rates_->frame(InputRates::Clock::now());
  if (!builder_) {
    ROS_WARN_THROTTLE(5.0, "no intrinsics yet: waiting for %s (or set ~camera_info_file)",
                      camera_info_topic_.c_str());
    return;
  }
  // With ~stop_when: quality the node keeps collecting while it fits (the worker has its own copy
  // of the pairs): the vehicle drives on, and the next fit wants more pairs anyway. Otherwise the
  // fit in progress is the result.
  if (state_ == CalibrationStatus::DONE) return;
  if (state_ == CalibrationStatus::OPTIMIZING && params_.stop_when != StopWhen::kQuality) return;
  if (params_.mode == NodeMode::kMonitor &&
      !ensureMonitoring(tfFrameId(image->header.frame_id), tfFrameId(clusters->header.frame_id))) {
    return;
  }
  if (stored_stamps_ns_.count(static_cast<long long>(image->header.stamp.toNSec())) != 0) {
    ROS_DEBUG("frame %.3f is already in the dataset", image->header.stamp.toSec());
    return;
  }
  if (stored_spacing_ && stored_spacing_->tooClose(image->header.stamp.toSec())) {
    ROS_DEBUG("frame %.3f is within the skip rule of a resumed pair", image->header.stamp.toSec());
    return;
  }
  const std::uint64_t nonfinite_before = builder_->counts().nonfinite_points_dropped;
  const OfferOutcome outcome = builder_->offer([&] {
    return decodeFrame(*image, *mask, *clusters, image_topic_, mask_topic_, clusters_topic_,
                       PointTimeField::parse(params_.core.point_time_field));
  });
  const std::uint64_t nonfinite = builder_->counts().nonfinite_points_dropped - nonfinite_before;
  if (nonfinite > 0) {
    if (const auto held_back = fault_throttle_.admit(clusters_topic_ + " NaN/inf points")) {
      ROS_WARN("%s: dropped %llu NaN/inf points of the cloud at %.3f (%llu so far)%s",
               clusters_topic_.c_str(), static_cast<unsigned long long>(nonfinite),
               clusters->header.stamp.toSec(),
               static_cast<unsigned long long>(builder_->counts().nonfinite_points_dropped),
               fault_throttle_.heldBackText(*held_back).c_str());
    }
  }
  reportFrameIdConflict();
  if (outcome.decision == GateDecision::kBadMessage) {
    // Decoder errors name their topic; size checks against camera_info concern the mask.
    const std::string where =
        outcome.error.find('/') != std::string::npos ? "" : " (" + mask_topic_ + ")";
    const std::string line = bad_frames_.report(image->header.stamp.toSec(), where, outcome.error,
                                                FaultThrottle::Clock::now());
    if (!line.empty()) ROS_WARN("%s", line.c_str());
    return;
  }
  if (outcome.decision != GateDecision::kKept) {
    ROS_DEBUG("frame %.3f: %s (mask %d people, clusters %d)", image->header.stamp.toSec(),
              toString(outcome.decision), outcome.mask_people, outcome.cluster_people);
    // Recorded once the builder holds it (after its motion, within its bound): ~resume and
    // calibrate_bag on the bag pair it by association as this session does.
    if ((outcome.candidate || outcome.skipped_held) && state_ != CalibrationStatus::MONITORING &&
        recorder_->enabled()) {
      candidate_messages_[outcome.frame_index] = {image, mask, clusters};
      recordHeldCandidates();
    }
    return;
  }
  if (state_ != CalibrationStatus::MONITORING) {
    stored_stamps_ns_.insert(static_cast<long long>(image->header.stamp.toNSec()));
    camera_frame_ = builder_->cameraFrame();
    lidar_frame_ = builder_->lidarFrame();
    // Recorded when the pair is finished: with motion, once the scans after it have arrived.
    kept_messages_.push_back({image, mask, clusters});
    ROS_DEBUG("kept frame %.3f (%d people): %s", image->header.stamp.toSec(), outcome.mask_people,
              progressLine().c_str());
  }
  handleFinishedPairs();
}

// Where the people were so far and what is missing, before a fit tells more: coverage only (the
// verdict without intervals is at best usable). Cheap (mask pixel counts), every
// ~quality_check_every_pairs kept pairs.
void CalibrationNode::assessCollection() {
  if (params_.stop_when != StopWhen::kQuality) return;
  const std::size_t n = builder_->pairs().size();
  if (n < collecting_quality_pairs_ + static_cast<std::size_t>(params_.quality_check_every_pairs)) return;
  collecting_quality_pairs_ = n;
  QualityAssessment q;
  q.coverage = computeCoverage(builder_->camera(), builder_->pairs(), {}, std::nullopt,
                               params_.core.quality.coverage);
  q.verdict = judgeQuality(q.coverage, std::nullopt, params_.core.quality.verdict);
  collecting_quality_ = std::move(q);
}

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
