// calibration_node: the drift watch (~mode: monitor, or ~monitor_after_calibration). Kept pairs go
// through the same ingest path as for a calibration, then to a DriftWatchWorker; the timer reads
// its snapshot, logs changes of state, and accepts a confirmed new extrinsic with ~auto_update
// (or on ~accept_update): published on /tf_static by the same publisher (never a second
// parent) and written to ~output_file with its history.

#include "thermal_lidar_calibration/node/calibration_node.hpp"

#include "thermal_lidar_calibration/app/parameters/association_parameters.hpp"
#include "thermal_lidar_calibration/app/report/quality_output.hpp"
#include "thermal_lidar_calibration/app/report/static_transform_command.hpp"
#include "thermal_lidar_calibration/ros/msg_conversion.hpp"

#include <diagnostic_msgs/DiagnosticStatus.h>

#include <cstdio>

namespace thermal_lidar_calibration {
namespace ros_io {
namespace {

std::string changeText(const DriftChange& c) {
  char text[160];
  std::snprintf(text, sizeof(text),
                "%.3f deg (about camera x, y, z: %.3f, %.3f, %.3f), translation [%.2f, %.2f, %.2f] cm",
                c.angle_deg, c.rotation_deg.x(), c.rotation_deg.y(), c.rotation_deg.z(),
                c.translation_cm.x(), c.translation_cm.y(), c.translation_cm.z());
  return text;
}

// What the watch measured last: the confirmed new extrinsic against the reference when there is
// one, else the latest window's fit (zeros before the first test).
struct LatestDrift {
  DriftChange change;
  double loss_reference = 0.0, loss_fit = 0.0;
};
LatestDrift latestDrift(const DriftWatchWorker::Snapshot& s) {
  if (s.candidate) return {s.candidate->change, s.candidate->loss_reference, s.candidate->loss_fit};
  if (s.last) return {s.last->test.change, s.last->test.loss_reference, s.last->test.loss_fit};
  return {};
}

// Issue 21: a change of the camera's time offset, in words, with what to do.
std::string timingChangeText(double time_offset_s, double change_s) {
  char text[400];
  std::snprintf(text, sizeof(text),
                "the camera's time offset changed by %+.0f ms (from %+.0f to %+.0f ms: a camera driver restarted "
                "with another latency?); the extrinsic fits at the new offset, it did not move: set "
                "~time_offset_s to %.4f (time_offset_mode fixed) or fix the driver",
                1000.0 * change_s, 1000.0 * time_offset_s, 1000.0 * (time_offset_s + change_s), time_offset_s + change_s);
  return text;
}

// A confirmed change with a new extrinsic to take (~accept_update).
bool updateAvailable(const DriftWatchWorker::Snapshot& s) {
  return s.candidate.has_value() && s.state == DriftState::kError;
}

}  // namespace

void CalibrationNode::startMonitoring(const Extrinsic& reference, const std::string& origin,
                                      std::optional<double> time_offset_s) {
  if (params_.core.calibration.time_offset.mode == TimeOffsetMode::kNone) time_offset_s.reset();
  // Issue 23: the watch pairs by association at the reference as the calibration did, so it gets
  // the frames the count rule passes over too.
  drift_ = std::make_unique<DriftWatchWorker>(builder_->camera(), reference, params_.core.drift,
                                              params_.core.calibration, time_offset_s,
                                              associationIfAsked(params_.core));
  drift_reference_ = origin;
  last_drift_state_ = DriftState::kOk;
  last_timing_state_ = DriftState::kOk;
  if (builder_->frameIdsLocked()) builder_->takePairs();  // the calibration's pairs are done
  builder_->takeCandidates();                              // and so are its candidates
  // The watch pairs the frames the skip rule lets through, as its windows are sized for them:
  // the skipped ones are neither decoded nor held from here on.
  builder_->keepSkippedFrames(false);
  builder_->takeSkippedFrames();
  kept_messages_.clear();  // a watch never records
  candidate_messages_.clear();
  finished_pairs_ = 0;
  ROS_INFO("drift watch: watching the extrinsic from %s (tests of the latest %d kept pairs every "
           "%d; ~auto_update %s)",
           origin.c_str(), params_.core.drift.window_pairs, params_.core.drift.period_pairs,
           params_.auto_update ? "on" : "off: a confirmed change waits for ~accept_update");
  setState(CalibrationStatus::MONITORING, "monitoring the extrinsic from " + origin);
}

std::optional<double> CalibrationNode::configuredTimeOffset() const {
  const TimeOffsetConfig& t = params_.core.calibration.time_offset;
  return t.mode == TimeOffsetMode::kFixed ? std::optional<double>(t.offset_s) : std::nullopt;
}

// ~mode: monitor without a running watch: its reference is ~reference_file, else the tf tree's
// transform between the frames of this frame. False (and a throttled warning) while there is none.
bool CalibrationNode::ensureMonitoring(const std::string& camera_frame,
                                       const std::string& lidar_frame) {
  if (drift_) return true;
  if (reference_) {
    startMonitoring(*reference_, "~reference_file " + params_.reference_file,
                    reference_time_offset_s_ ? reference_time_offset_s_ : configuredTimeOffset());
    return true;
  }
  std::string error;
  if (const auto live = tf_publisher_->lookupExtrinsic(lidar_frame, camera_frame, &error)) {
    startMonitoring(*live, "live tf '" + lidar_frame + "' -> '" + camera_frame + "'", configuredTimeOffset());
    return true;
  }
  const std::string text = "drift watch: no reference yet: ~reference_file is not set and the tf "
                           "tree has no transform from '" + lidar_frame + "' to '" + camera_frame +
                           "' (" + error + "); publish the robot's tf or set ~reference_file";
  if (const auto held_back = fault_throttle_.admit("drift watch without reference")) {
    ROS_WARN("%s%s", text.c_str(), fault_throttle_.heldBackText(*held_back).c_str());
  }
  if (state_message_ != text) setState(CalibrationStatus::MONITORING, text);
  return false;
}

// A kept pair in monitor state: to the watch once the frame ids are settled (3 agreeing pairs),
// never into the dataset bag (a watch runs for hours).
void CalibrationNode::monitorKeptPairs() {
  if (!drift_ || !builder_->frameIdsLocked()) return;
  camera_frame_ = builder_->cameraFrame();
  lidar_frame_ = builder_->lidarFrame();
  for (CalibrationPair& pair : inOfferOrder(builder_->takePairs(), builder_->takeCandidates())) {
    drift_->submit(std::move(pair));
  }
}

void CalibrationNode::updateDrift() {
  if (!drift_) return;
  const DriftWatchWorker::Snapshot s = drift_->snapshot();
  if (!s.error.empty() && s.error != drift_error_) {
    drift_error_ = s.error;
    ROS_ERROR("drift watch: a test failed: %s", s.error.c_str());
  }
  if (s.timing_state != last_timing_state_) {
    last_timing_state_ = s.timing_state;
    if (s.timing_state != DriftState::kOk && s.time_offset_s && s.timing_change_s) {
      ROS_WARN("drift watch timing %s: %s", toString(s.timing_state),
               timingChangeText(*s.time_offset_s, *s.timing_change_s).c_str());
    } else {
      ROS_INFO("drift watch timing %s: the camera's time offset holds", toString(s.timing_state));
    }
  }
  if (s.state != last_drift_state_) {
    const DriftChange change = latestDrift(s).change;
    const double loss_ref = s.last ? s.last->test.loss_reference : 0.0;
    const double loss_fit = s.last ? s.last->test.loss_fit : 0.0;
    const char* what = s.state == DriftState::kError ? "confirmed: the extrinsic no longer fits"
                       : s.state == DriftState::kWarn ? "a change is suspected"
                                                      : "the extrinsic fits again";
    const std::string line = std::string("drift watch ") + toString(s.state) + ": " + what +
                             "; change " + changeText(change) + "; loss of the reference " +
                             std::to_string(loss_ref) + " px vs the new fit " +
                             std::to_string(loss_fit) + " px";
    if (s.state == DriftState::kError) {
      ROS_ERROR("%s%s", line.c_str(),
                !s.candidate ? "; no new extrinsic yet (the fit is still settling, or the change is "
                               "beyond monitor_max_update_*: then calibrate again)"
                : params_.auto_update ? ""
                                      : "; call ~accept_update to publish the new extrinsic");
    } else if (s.state == DriftState::kWarn) {
      ROS_WARN("%s", line.c_str());
    } else {
      ROS_INFO("%s", line.c_str());
    }
    last_drift_state_ = s.state;
    state_message_ = line;
    publishStatus();  // before an auto-update below turns it back to OK: ~status shows the ERROR
    diagnostics_->publishNow();
  }
  if (s.update_ready && params_.auto_update) {
    const std::string outcome = acceptDriftUpdate("auto_update");
    ROS_INFO("drift watch: %s", outcome.c_str());
  }
}

std::string CalibrationNode::acceptDriftUpdate(const std::string& by) {
  if (!drift_) return "refused: the drift watch is not running";
  const auto update = drift_->accept();
  if (!update) {
    return "refused: no confirmed change to accept (drift state " +
           std::string(toString(drift_->snapshot().state)) + ")";
  }
  drift_history_.push_back({*update, by, ros::WallTime::now().toSec()});
  last_drift_state_ = DriftState::kOk;  // the watch starts over from the new extrinsic
  const Extrinsic& now = update->accepted.extrinsic;
  drift_reference_ = "drift update " + std::to_string(drift_history_.size()) + " (" + by + ")";
  CalibratedTfPublisher::Decision decision;
  tf_publisher_->publish(now, lidar_frame_, camera_frame_, &decision);
  published_child_ = decision.child_frame;
  overlay_->setEstimate(now);
  std::string file = "written to " + params_.output_file;
  try {
    writeDriftUpdateFile(params_.output_file, lidar_frame_, camera_frame_, drift_history_);
  } catch (const std::exception& e) {
    file = std::string("NOT written (") + e.what() + "); free the path and accept again later";
    ROS_ERROR("drift update: result file %s", file.c_str());
  }
  const std::string text =
      "new extrinsic accepted (" + by + "): change " + changeText(update->accepted.change) +
      ", loss " + std::to_string(update->accepted.loss_reference) + " -> " +
      std::to_string(update->accepted.loss_fit) + " px on " +
      std::to_string(update->accepted.pairs) + " pairs" +
      (update->accepted.complete ? "" : " (early: a final fit follows)") + "; published '" +
      lidar_frame_ + "' -> '" + published_child_ + "'" +
      (decision.reason.empty() ? "" : " (" + decision.reason + ")") + "; " + file +
      "; equivalent: " + staticTransformPublisherCommand(now, lidar_frame_, published_child_);
  setState(CalibrationStatus::MONITORING, text);
  diagnostics_->publishNow();
  return text;
}

bool CalibrationNode::onAcceptUpdate(std_srvs::Trigger::Request& /*req*/,
                                     std_srvs::Trigger::Response& res) {
  res.message = acceptDriftUpdate("accept_update");
  res.success = res.message.rfind("refused", 0) != 0;
  ROS_INFO("~accept_update: %s", res.message.c_str());
  return true;
}

void CalibrationNode::fillDriftStatus(CalibrationStatus& msg) const {
  if (!drift_) return;
  const DriftWatchWorker::Snapshot s = drift_->snapshot();
  msg.drift_state = toString(s.state);
  msg.drift_reference = drift_reference_;
  msg.drift_timing_state = s.time_offset_s ? toString(s.timing_state) : "";
  msg.drift_time_offset_change_ms = s.timing_change_s ? 1000.0 * *s.timing_change_s : 0.0;
  msg.drift_pairs_seen = static_cast<std::uint32_t>(s.pairs_seen);
  msg.drift_association_pairs = static_cast<std::uint32_t>(s.association_pairs);
  msg.drift_pairs_in_window = static_cast<std::uint32_t>(s.pairs_in_window);
  msg.drift_tests = static_cast<std::uint32_t>(s.tests);
  const LatestDrift latest = latestDrift(s);
  msg.drift_rotation_change_deg = latest.change.angle_deg;
  for (int i = 0; i < 3; ++i) {
    msg.drift_rotation_change_axes_deg[i] = latest.change.rotation_deg[i];
    msg.drift_translation_change_cm[i] = latest.change.translation_cm[i];
  }
  msg.drift_loss_reference = latest.loss_reference;
  msg.drift_loss_fit = latest.loss_fit;
  msg.drift_update_available = updateAvailable(s);
  msg.drift_pairs_waiting = static_cast<std::uint32_t>(s.queued + (s.testing ? 1 : 0));
  msg.drift_update_ready = s.update_ready;
  msg.drift_updates = static_cast<std::uint32_t>(drift_history_.size());
  if (s.candidate) {
    msg.drift_update_model = toString(s.candidate->model);
    if (s.candidate->uncertainty) {
      for (int i = 0; i < 3; ++i) {
        msg.drift_update_rotation_halfwidth_deg[i] = s.candidate->uncertainty->rotation_deg[i];
        msg.drift_update_translation_halfwidth_cm[i] = s.candidate->uncertainty->translation_cm[i];
      }
    }
  }
  for (int i = 0; i < 3; ++i) {
    msg.rotation_vector[i] = s.reference.rotation_vector[i];
    msg.translation[i] = s.reference.translation[i];
  }
}

void CalibrationNode::diagnoseDrift(NodeDiagnostics::Status& status) const {
  using diagnostic_msgs::DiagnosticStatus;
  if (!drift_) {
    status.summary(DiagnosticStatus::OK, params_.mode == NodeMode::kMonitor
                                             ? "waiting for a reference and intrinsics"
                                             : "not monitoring (~mode: calibrate)");
    return;
  }
  const DriftWatchWorker::Snapshot s = drift_->snapshot();
  const LatestDrift latest = latestDrift(s);
  const DriftChange& change = latest.change;
  const std::uint8_t level = s.state == DriftState::kError  ? DiagnosticStatus::ERROR
                             : s.state == DriftState::kWarn ? DiagnosticStatus::WARN
                                                            : DiagnosticStatus::OK;
  status.summary(level, std::string(toString(s.state)) + ": change " + changeText(change));
  status.add("reference", drift_reference_);
  status.addf("loss of the reference (px)", "%.4f", latest.loss_reference);
  status.addf("loss of the new fit (px)", "%.4f", latest.loss_fit);
  status.add("pairs seen", s.pairs_seen);
  status.add("of which by association", s.association_pairs);
  status.add("pairs in window", s.pairs_in_window);
  status.add("tests", s.tests);
  status.add("update available", updateAvailable(s) ? "yes: ~accept_update" : "no");
  if (s.candidate) {
    status.add("new fit model", toString(s.candidate->model));
    if (s.candidate->uncertainty) status.add("new fit 95 % half-widths", formatHalfWidths(*s.candidate->uncertainty));
  }
  status.add("updates accepted", drift_history_.size());
  if (s.candidates_refused > 0) {
    status.add("new fits refused (beyond monitor_max_update_*)", s.candidates_refused);
    if (s.state == DriftState::kError && !s.candidate) {
      status.summary(level, std::string("ERROR: the extrinsic no longer fits and the change is "
                                        "beyond what the watch refits: calibrate again"));
    }
  }
  if (s.time_offset_s) {  // issue 21: timing apart from the extrinsic
    status.addf("time offset of the reference (ms)", "%.1f", 1000.0 * *s.time_offset_s);
    status.add("timing", toString(s.timing_state));
    if (s.timing_change_s) {
      status.addf("time offset change (ms)", "%.1f", 1000.0 * *s.timing_change_s);
      if (s.state == DriftState::kOk && s.timing_state != DriftState::kOk) {
        status.summary(s.timing_state == DriftState::kError ? DiagnosticStatus::ERROR : DiagnosticStatus::WARN,
                       timingChangeText(*s.time_offset_s, *s.timing_change_s));
      }
    }
  }
  status.addf("watch CPU time (s)", "%.2f", s.seconds);
  if (s.dropped > 0) status.add("pairs dropped (watch behind)", s.dropped);
}

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
