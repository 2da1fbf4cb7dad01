// calibration_node: ~status, lifecycle state and the periodic progress log.

#include "thermal_lidar_calibration/node/calibration_node.hpp"

#include "thermal_lidar_calibration/app/report/timing_text.hpp"

#include <cstdio>
#include <sstream>

namespace thermal_lidar_calibration {
namespace ros_io {

const char* stateName(std::uint8_t state) {
  switch (state) {
    case CalibrationStatus::COLLECTING: return "collecting";
    case CalibrationStatus::OPTIMIZING: return "optimizing";
    case CalibrationStatus::DONE: return "done";
    case CalibrationStatus::FAILED: return "failed";
    case CalibrationStatus::MONITORING: return "monitoring";
  }
  return "unknown";
}

const QualityAssessment* CalibrationNode::latestQuality() const {
  if (quality_) return &*quality_;
  if (collecting_quality_) return &*collecting_quality_;
  return nullptr;
}

std::string CalibrationNode::progressLine() const {
  std::ostringstream s;
  const std::size_t kept = builder_ ? builder_->pairs().size() : 0;
  s << "kept " << kept << "/" << nextFitPairs();
  if (!builder_) return s.str() + " (no intrinsics yet)";
  // ~stop_when quality: the latest fit's verdict, or before the first fit the coverage so far.
  const QualityAssessment* q = params_.stop_when == StopWhen::kQuality ? latestQuality() : nullptr;
  if (q) {
    char thirds[64];
    std::snprintf(thirds, sizeof(thirds), "image thirds %.0f / %.0f / %.0f %%",
                  100 * q->coverage.thirdFraction(0), 100 * q->coverage.thirdFraction(1),
                  100 * q->coverage.thirdFraction(2));
    s << " (" << thirds << "; " << (quality_ ? "verdict " : "so far ")
      << toString(q->verdict.verdict);
    if (!q->verdict.reasons.empty()) s << ": " << q->verdict.reasons.front();
    s << ")";
  }
  const RejectionCounts& c = builder_->counts();
  s << "; rejected: unequal " << c[GateDecision::kCountMismatch] << ", none "
    << c[GateDecision::kNoPeople] << ", >H_max " << c[GateDecision::kTooManyPeople]
    << ", skipped " << c[GateDecision::kSkipped];
  if (c[GateDecision::kSmallCluster] > 0) s << ", small cluster " << c[GateDecision::kSmallCluster];
  if (c[GateDecision::kBadMessage] > 0) s << ", bad " << c[GateDecision::kBadMessage];
  if (pairs_resumed_ > 0) s << " (" << pairs_resumed_ << " resumed)";
  if (builder_->keepsAssociationCandidates()) {
    s << "; association candidates " << builder_->candidates().size();
    if (builder_->candidatesDropped() > 0) s << " (" << builder_->candidatesDropped() << " dropped for the bound)";
    if (builder_->keepsSkippedFrames()) s << "; skipped frames held " << builder_->skippedFrames().size();
  }
  return s.str();
}

void CalibrationNode::setState(std::uint8_t state, const std::string& message) {
  state_ = state;
  state_message_ = message;
  publishStatus();
}

void CalibrationNode::logProgress(bool force) {
  const ros::WallTime now = ros::WallTime::now();
  if (!force && (now - last_progress_log_).toSec() < params_.progress_log_period_s) return;
  if (state_ == CalibrationStatus::COLLECTING || state_ == CalibrationStatus::FAILED) {
    const std::uint64_t considered = builder_ ? builder_->counts().considered() : 0;
    if (!force && considered == last_logged_considered_) return;  // nothing new
    last_logged_considered_ = considered;
    ROS_INFO("%s: %s", stateName(state_), progressLine().c_str());
  } else if (state_ == CalibrationStatus::OPTIMIZING) {
    const auto p = worker_.progress();
    if (!p) return;
    ROS_INFO("optimizing: %s generation %d/%d, best loss %.3f px, %llu evaluations",
             p->stage.c_str(), p->generation, p->generations_total, p->best_loss,
             static_cast<unsigned long long>(p->evaluations));
  } else if (state_ == CalibrationStatus::MONITORING && drift_) {
    const DriftWatchWorker::Snapshot s = drift_->snapshot();
    if (!force && s.pairs_seen == last_logged_considered_) return;
    last_logged_considered_ = s.pairs_seen;
    ROS_INFO("monitoring: drift %s, %llu kept pairs seen, %llu tests, latest change %.3f deg / "
             "%.2f cm (reference %s)",
             toString(s.state), static_cast<unsigned long long>(s.pairs_seen),
             static_cast<unsigned long long>(s.tests),
             s.last ? s.last->test.change.angle_deg : 0.0,
             s.last ? s.last->test.change.translation_cm.norm() : 0.0, drift_reference_.c_str());
  } else {
    return;
  }
  last_progress_log_ = now;
}

void CalibrationNode::publishStatus() {
  CalibrationStatus msg;
  msg.header.stamp = ros::Time::now();
  msg.state = state_;
  msg.state_name = stateName(state_);
  msg.message = state_message_;
  msg.pairs_required = static_cast<std::uint32_t>(params_.core.pairs_required);
  if (builder_) {
    const RejectionCounts& c = builder_->counts();
    msg.pairs_kept = static_cast<std::uint32_t>(builder_->pairs().size());
    msg.frames_considered = static_cast<std::uint32_t>(c.considered());
    msg.rejected_count_mismatch = static_cast<std::uint32_t>(c[GateDecision::kCountMismatch]);
    msg.rejected_no_people = static_cast<std::uint32_t>(c[GateDecision::kNoPeople]);
    msg.rejected_too_many_people = static_cast<std::uint32_t>(c[GateDecision::kTooManyPeople]);
    msg.rejected_skipped = static_cast<std::uint32_t>(c[GateDecision::kSkipped]);
    msg.rejected_small_cluster = static_cast<std::uint32_t>(c[GateDecision::kSmallCluster]);
    msg.rejected_bad_message = static_cast<std::uint32_t>(c[GateDecision::kBadMessage]);
    msg.nonfinite_points_dropped = static_cast<std::uint32_t>(c.nonfinite_points_dropped);
    msg.association_candidates = static_cast<std::uint32_t>(builder_->candidates().size());
    msg.association_candidates_dropped = static_cast<std::uint32_t>(builder_->candidatesDropped());
  }
  if (state_ == CalibrationStatus::OPTIMIZING) {
    if (const auto p = worker_.progress()) {
      msg.stage = p->stage;
      msg.generation = static_cast<std::uint32_t>(p->generation);
      msg.generations_total = static_cast<std::uint32_t>(p->generations_total);
      msg.best_loss = p->best_loss;
      msg.evaluations = p->evaluations;
      for (int i = 0; i < 3; ++i) {
        msg.rotation_vector[i] = p->best.rotation_vector[i];
        msg.translation[i] = p->best.translation[i];
      }
    }
  } else if (result_) {
    msg.best_loss = result_->loss;
    msg.final_loss = result_->loss;
    msg.evaluations = result_->evaluations;
    for (int i = 0; i < 3; ++i) {
      msg.rotation_vector[i] = result_->extrinsic.rotation_vector[i];
      msg.translation[i] = result_->extrinsic.translation[i];
    }
  }
  if (input_rates_) {  // input_rates_'s order: image, mask, clusters
    msg.images_received = static_cast<std::uint32_t>(input_rates_->total(0));
    msg.masks_received = static_cast<std::uint32_t>(input_rates_->total(1));
    msg.clusters_received = static_cast<std::uint32_t>(input_rates_->total(2));
  }
  msg.intrinsics_known = builder_ != nullptr;
  msg.pairs_resumed = static_cast<std::uint32_t>(pairs_resumed_);
  msg.dataset_bag = params_.dataset_bag;
  msg.recording = recorder_ && recorder_->recording();
  msg.pairs_in_bag = recorder_ ? static_cast<std::uint32_t>(recorder_->pairsInBag()) : 0;
  msg.recording_error = recorder_ ? recorder_->stopReason() : "";
  msg.output_file = params_.output_file;
  msg.child_frame = result_ && result_published_ ? published_child_ : "";
  if (const QualityAssessment* q = latestQuality()) {
    for (int i = 0; i < 3; ++i) msg.coverage_third_fractions[i] = q->coverage.thirdFraction(i);
    msg.quality_missing = q->verdict.reasons.empty() ? "" : q->verdict.reasons.front();
  }
  if (result_) {
    const std::optional<Uncertainty> u = quality_ ? quality_->uncertainty : std::nullopt;
    msg.time_offset_mode = toString(result_->time_offset_mode);
    msg.time_offset_s = result_->time_offset_s;
    msg.time_offset_halfwidth_ms = u && u->timed ? u->time_offset_ms : 0.0;
    msg.time_offset_text = timeOffsetText(*result_, u);
  }
  msg.pairs_waiting_for_motion = builder_ ? static_cast<std::uint32_t>(builder_->pendingPairs()) : 0;
  fillDriftStatus(msg);
  status_pub_.publish(msg);
}

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
