// calibration_node: the optimization run on the worker thread and its result (/tf_static,
// the result file, the overlay estimate).

#include "thermal_lidar_calibration/node/calibration_node.hpp"

#include "thermal_lidar_calibration/app/report/static_transform_command.hpp"
#include "thermal_lidar_calibration/app/report/timing_text.hpp"

namespace thermal_lidar_calibration {
namespace ros_io {

std::size_t CalibrationNode::nextFitPairs() const {
  return std::max<std::size_t>(next_fit_pairs_, static_cast<std::size_t>(params_.core.pairs_required));
}

// The calibration in use, to compare with: ~reference_file, else what the tf tree holds between
// the two frames (not this node's own earlier result: only while it has not published under the
// camera frame itself).
std::optional<JobReference> CalibrationNode::runReference() const {
  if (reference_) return JobReference{*reference_, "file", params_.reference_file};
  const std::string lidar = builder_->lidarFrame(), camera = builder_->cameraFrame();
  if (lidar.empty() || camera.empty() || published_child_ == camera) return std::nullopt;
  std::string ignored;
  const std::optional<Extrinsic> in_tf = tf_publisher_->lookupExtrinsic(lidar, camera, &ignored);
  if (!in_tf) return std::nullopt;
  JobReference reference{*in_tf, "tf", "tf " + lidar + " -> " + camera};
  ROS_INFO("comparing with the calibration in the tf tree (%s)", reference.origin.c_str());
  return reference;
}

bool CalibrationNode::initialTfInTree() const {
  if (!builder_ || builder_->lidarFrame().empty() || builder_->cameraFrame().empty()) return false;
  std::string error;
  return tf_publisher_->lookupExtrinsic(builder_->lidarFrame(), builder_->cameraFrame(), &error).has_value();
}

std::optional<InitialExtrinsic> CalibrationNode::initialExtrinsic() {
  if (initial_file_) return initial_file_;
  if (!params_.initial_from_tf || initial_tf_) return initial_tf_;
  const std::string lidar = builder_->lidarFrame(), camera = builder_->cameraFrame();
  std::string error = "this node's own result is all the tf tree holds between them";
  // The same lookup as the reference's: p_C = R p_L + t, through whatever chain links the frames.
  const std::optional<Extrinsic> in_tf =
      published_child_ == camera ? std::nullopt : tf_publisher_->lookupExtrinsic(lidar, camera, &error);
  if (!in_tf) {
    if (!initial_tf_warned_) {  // once: ~stop_when quality fits again and again
      ROS_WARN("~initial_from_tf: no tf between '%s' and '%s' (%s); association starts from the paper's first fit",
               lidar.c_str(), camera.c_str(), error.c_str());
    }
    initial_tf_warned_ = true;
    return std::nullopt;
  }
  initial_tf_ = InitialExtrinsic{*in_tf, std::nullopt, "tf " + lidar + " -> " + camera};
  ROS_INFO("~initial_from_tf: association may start from the %s (if the count rule's pairs agree with it)",
           initial_tf_->origin.c_str());
  return initial_tf_;
}

std::string CalibrationNode::startOptimization(const std::string& why) {
  if (state_ == CalibrationStatus::OPTIMIZING) return "refused: already optimizing";
  if (state_ == CalibrationStatus::MONITORING) {
    return "refused: monitoring (the drift watch refits by itself; ~accept_update takes a confirmed "
           "change; ~reset restarts the watch)";
  }
  if (worker_.busy()) return "refused: the previous optimization is still stopping; try again";
  if (!builder_) return "refused: no camera intrinsics yet (" + camera_info_topic_ + ")";
  const std::size_t n = builder_->pairs().size();
  if (static_cast<int>(n) < params_.min_pairs_to_calibrate) {
    return "refused: only " + std::to_string(n) + " pairs kept, at least " +
           std::to_string(params_.min_pairs_to_calibrate) + " needed (~min_pairs_to_calibrate)";
  }
  discard_outcome_ = false;
  CalibrationJobRequest job;
  job.camera = builder_->camera();
  job.pairs = builder_->pairs();
  // Copies share the images (cv::Mat): the candidates stay for the next fit (~stop_when quality).
  job.candidates = inOfferOrder(builder_->candidates(), builder_->skippedFrames());
  job.candidates_collected = builder_->keepsAssociationCandidates();
  job.parameters = params_.core;
  job.reference = runReference();
  job.initial = initialExtrinsic();
  job.lidar_frame = lidar_frame_;
  job.camera_frame = camera_frame_;
  job.source = "live";
  job.report_title = "calibration_node " + ros::this_node::getName();
  job.output_file = params_.output_file;
  job.report_dir = params_.report_dir;
  const bool candidates = job.candidates_collected;
  const std::size_t n_candidates = job.candidates.size();
  worker_.start(std::move(job));
  logProgress(true);
  setState(CalibrationStatus::OPTIMIZING, "optimizing " + std::to_string(n) + " pairs (" + why + ")");
  if (candidates) {
    ROS_INFO("optimizing %zu pairs and %zu association candidates on a worker thread (%s)", n, n_candidates,
             why.c_str());
  } else {
    ROS_INFO("optimizing %zu pairs on a worker thread (%s)", n, why.c_str());
  }
  return "";
}

void CalibrationNode::handleOutcome(CalibrationWorker::Outcome outcome) {
  if (discard_outcome_) {
    discard_outcome_ = false;
    return;
  }
  if (!outcome.result) {
    ROS_ERROR("calibration failed: %s", outcome.error.c_str());
    setState(CalibrationStatus::FAILED, "calibration failed: " + outcome.error);
    return;
  }
  if (outcome.result->stopped) {
    setState(CalibrationStatus::COLLECTING, "optimization stopped");
    return;
  }
  result_ = std::move(outcome.result);
  quality_ = std::move(outcome.quality);
  result_context_ = std::move(outcome.context);
  if (!outcome.quality_error.empty()) ROS_WARN("%s", outcome.quality_error.c_str());
  if (quality_) {
    ROS_INFO("verdict %s: %s", toString(quality_->verdict.verdict),
             quality_->verdict.reasons.empty() ? "" : quality_->verdict.reasons.front().c_str());
  }
  const std::string& write_error = outcome.result_file_error;
  if (outcome.result_file_written) {
    ROS_INFO("result written to %s", params_.output_file.c_str());
  } else {
    ROS_ERROR("result file not written: %s", write_error.c_str());
  }
  if (!params_.report_dir.empty()) {
    if (outcome.report_error.empty()) {
      ROS_INFO("report written: %s/index.html", params_.report_dir.c_str());
    } else {
      ROS_ERROR("report not written: %s", outcome.report_error.c_str());
    }
  }
  overlay_->setEstimate(result_->extrinsic);
  overlay_->setTimeOffset(result_->time_offset_mode == TimeOffsetMode::kNone ? std::nullopt
                                                                              : std::optional<double>(result_->time_offset_s));
  ROS_INFO("camera time offset: %s",
           timeOffsetText(*result_, quality_ ? quality_->uncertainty : std::nullopt).c_str());
  const std::string late = timeOffsetWarning(*result_);
  if (!late.empty()) ROS_WARN("%s", late.c_str());
  result_published_ = false;
  if (tfCheckWaitOver()) publishResult();
  // The count rule's pairs this fit used (collecting went on while it ran with ~stop_when:
  // quality): what ~max_pairs and the next fit count, not the association pairs made from them.
  const std::size_t n = outcome.pairing.counts;
  if (params_.stop_when == StopWhen::kQuality && quality_ &&
      quality_->verdict.verdict != Verdict::kGood && n < static_cast<std::size_t>(params_.max_pairs)) {
    // Not good yet: the result is out (a better one replaces it), and collecting goes on.
    next_fit_pairs_ = std::min<std::size_t>(n + params_.quality_check_every_pairs, params_.max_pairs);
    const std::string missing =
        quality_->verdict.reasons.empty() ? "" : ": " + quality_->verdict.reasons.front();
    setState(CalibrationStatus::COLLECTING,
             std::string("verdict ") + toString(quality_->verdict.verdict) + " at " +
                 std::to_string(n) + " pairs" + missing + "; collecting on (next fit at " +
                 std::to_string(next_fit_pairs_) + " pairs, the last at ~max_pairs " +
                 std::to_string(params_.max_pairs) + ")" +
                 (write_error.empty() ? "" : "; result file NOT written (" + write_error + ")"));
    ROS_INFO("%s", state_message_.c_str());
    // The pairs kept during the fit may already be enough for the next one.
    if (builder_->pairs().size() >= nextFitPairs()) {
      startOptimization("~stop_when quality: " + std::to_string(nextFitPairs()) + " pairs, fitting again");
    }
    return;
  }
  setState(CalibrationStatus::DONE,
           "done: loss " + std::to_string(result_->loss) + " px" +
               (quality_ ? std::string(", verdict ") + toString(quality_->verdict.verdict) : "") +
               (write_error.empty() ? ""
                                    : "; result file NOT written (" + write_error +
                                          "); free the path and call ~save"));
  if (params_.monitor_after_calibration) {
    startMonitoring(result_->extrinsic, "this node's calibration",
                    result_->time_offset_mode == TimeOffsetMode::kNone ? std::nullopt
                                                                        : std::optional<double>(result_->time_offset_s));
  }
}

bool CalibrationNode::tfCheckWaitOver() const {
  if ((ros::WallTime::now() - start_time_).toSec() < params_.tf_check_wait_s) return false;
  return first_input_time_ && (ros::Time::now() - *first_input_time_).toSec() >= params_.tf_check_wait_s;
}

void CalibrationNode::watchTf() {
  if (!tf_conflict_.empty()) return;
  const auto conflict = tf_publisher_->conflictAfterPublishing();
  if (!conflict) return;
  const std::string moved_to = tf_publisher_->moveToFallback();
  tf_conflict_ = *conflict + "; the result moved to '" + lidar_frame_ + "' -> '" + moved_to +
                 "' (tf listeners that already hold the old edge keep it until they restart)";
  published_child_ = moved_to;
  ROS_ERROR("second parent: %s", tf_conflict_.c_str());
  setState(state_, "error: second parent: " + tf_conflict_);
  diagnostics_->publishNow();
}

void CalibrationNode::diagnoseTf(NodeDiagnostics::Status& status) const {
  using diagnostic_msgs::DiagnosticStatus;
  if (!tf_conflict_.empty()) {
    status.summary(DiagnosticStatus::ERROR, "second parent: " + tf_conflict_);
  } else if (result_ && result_published_) {
    status.summary(DiagnosticStatus::OK, "published '" + lidar_frame_ + "' -> '" + published_child_ + "'");
  } else if (result_) {
    status.summary(DiagnosticStatus::OK,
                   first_input_time_ ? "listening to the tf tree before publishing (~tf_check_wait_s of data time)"
                                     : "the result waits for input data: it is published after ~tf_check_wait_s of "
                                       "the data's own time, so a replayed bag's /tf_static is seen first");
  } else {
    status.summary(DiagnosticStatus::OK, "no result yet");
  }
  status.add("child_frame", result_published_ ? published_child_ : "");
}

void CalibrationNode::publishResult() {
  CalibratedTfPublisher::Decision decision;
  tf_publisher_->publish(result_->extrinsic, lidar_frame_, camera_frame_, &decision);
  published_child_ = decision.child_frame;
  result_published_ = true;
  if (!decision.reason.empty()) {
    ROS_WARN("%s: the result is published as '%s' -> '%s' instead, never as a second parent",
             decision.reason.c_str(), lidar_frame_.c_str(), published_child_.c_str());
  }
  const Eigen::Matrix3d R = result_->extrinsic.rotationMatrix();
  const Eigen::Vector3d& t = result_->extrinsic.translation;
  ROS_INFO("result (p_%s = R p_%s + t): R = [%.6f %.6f %.6f; %.6f %.6f %.6f; %.6f %.6f %.6f], "
           "t = [%.4f %.4f %.4f] m, loss %.3f px on %zu/%zu pairs, %.1f s; published on "
           "/tf_static; equivalent: %s",
           camera_frame_.c_str(), lidar_frame_.c_str(), R(0, 0), R(0, 1), R(0, 2), R(1, 0),
           R(1, 1), R(1, 2), R(2, 0), R(2, 1), R(2, 2), t.x(), t.y(), t.z(), result_->loss,
           result_->pairs_used, result_->pairs_collected, result_->seconds,
           staticTransformPublisherCommand(result_->extrinsic, lidar_frame_, published_child_).c_str());
}

std::string CalibrationNode::writeResult() {
  const std::string error = saveResultFile(params_.output_file, *result_, result_context_);
  if (error.empty()) {
    ROS_INFO("result written to %s", params_.output_file.c_str());
  } else {
    ROS_ERROR("result file not written: %s", error.c_str());
  }
  return error;
}

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
