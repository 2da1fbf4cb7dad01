// calibration_node: construction (parameters, subscriptions, services, timer) and the timer.

#include "thermal_lidar_calibration/node/calibration_node.hpp"

#include "thermal_lidar_calibration/app/report/timing_text.hpp"

#include "thermal_lidar_calibration/app/files/camera_info_file.hpp"
#include "thermal_lidar_calibration/app/files/result_file.hpp"
#include "thermal_lidar_calibration/app/parameters/unknown_parameters.hpp"
#include "thermal_lidar_calibration/app/files/writable_path.hpp"
#include "thermal_lidar_calibration/app/parameters/parameter_catalog.hpp"
#include "thermal_lidar_calibration/ros/msg_conversion.hpp"
#include "thermal_lidar_calibration/ros/node_parameter_source.hpp"

#include <diagnostic_msgs/DiagnosticStatus.h>

#include <sstream>

namespace thermal_lidar_calibration {
namespace ros_io {

CalibrationNode::CalibrationNode(ros::NodeHandle nh, ros::NodeHandle private_nh)
    : nh_(std::move(nh)), private_nh_(std::move(private_nh)), start_time_(ros::WallTime::now()) {
  readParameters();
  image_topic_ = nh_.resolveName("thermal/image_raw");
  mask_topic_ = nh_.resolveName("thermal/human_mask");
  clusters_topic_ = nh_.resolveName("lidar/human_clusters");
  camera_info_topic_ = nh_.resolveName("thermal/camera_info");

  diagnostics_ = std::make_unique<NodeDiagnostics>(nh_, private_nh_);
  tf_publisher_ = std::make_unique<CalibratedTfPublisher>(params_.child_frame);
  status_pub_ = private_nh_.advertise<CalibrationStatus>("status", 1, /*latch=*/true);
  overlay_ = std::make_unique<OverlayPublisher>(private_nh_, params_.overlay_max_points,
                                                clusters_topic_);
  if (!params_.reference_file.empty()) {
    try {
      reference_ = readExtrinsicFile(params_.reference_file);
      reference_time_offset_s_ = readAppliedTimeOffset(params_.reference_file);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("parameter 'reference_file': ") + e.what());
    }
  }
  if (!params_.core.initial_extrinsic_file.empty()) {
    try {
      initial_file_ = readInitialExtrinsic(params_.core.initial_extrinsic_file);
    } catch (const std::invalid_argument& e) {
      // readInitialExtrinsic says "initial_extrinsic_file: why"; the node's form names the key once.
      const std::string why = e.what();
      const std::string key = "initial_extrinsic_file: ";
      throw std::invalid_argument("parameter 'initial_extrinsic_file': " +
                                  (why.rfind(key, 0) == 0 ? why.substr(key.size()) : why));
    }
  }
  if (!params_.camera_info_file.empty()) {
    const CameraModel camera = loadCameraInfoFile(params_.camera_info_file);  // throws
    camera_info_msg_ = cameraInfoFromModel(camera);
    createBuilder(camera, params_.camera_info_file);
  }
  if (!params_.dataset_bag.empty() && params_.resume) resumeDataset();
  // A drift watch runs for hours: its pairs are not recorded.
  recorder_ = std::make_unique<DatasetRecorder>(
      params_.mode == NodeMode::kMonitor ? "" : params_.dataset_bag, params_.resume, pairs_resumed_);
  diagnostics_->add("dataset recording",
                    [this](NodeDiagnostics::Status& status) { recorder_->diagnose(status); });
  diagnostics_->add("frame ids", [this](NodeDiagnostics::Status& status) { diagnoseFrameIds(status); });
  input_rates_ = std::make_unique<InputRates>(
      std::vector<std::string>{image_topic_, mask_topic_, clusters_topic_}, InputRates::Clock::now());
  diagnostics_->add("inputs", [this](NodeDiagnostics::Status& status) { diagnoseInputs(status); });
  diagnostics_->add("calibration", [this](NodeDiagnostics::Status& status) { diagnoseCalibration(status); });
  diagnostics_->add("tf", [this](NodeDiagnostics::Status& status) { diagnoseTf(status); });
  diagnostics_->add("drift", [this](NodeDiagnostics::Status& status) { diagnoseDrift(status); });
  if (!builder_) {
    camera_info_sub_ = nh_.subscribe("thermal/camera_info", 1, &CalibrationNode::onCameraInfo, this);
  }

  synchronizer_ = std::make_unique<FrameSynchronizer>(
      params_.core.sync_queue_size, params_.core.sync_slop_s,
      [this](const sensor_msgs::Image::ConstPtr& image, const sensor_msgs::Image::ConstPtr& mask,
             const sensor_msgs::PointCloud2::ConstPtr& clusters) { onFrame(image, mask, clusters); });
  it_ = std::make_unique<image_transport::ImageTransport>(nh_);
  const auto queue = static_cast<std::uint32_t>(params_.core.sync_queue_size);
  image_sub_ = it_->subscribe("thermal/image_raw", queue, &CalibrationNode::onImage, this);
  mask_sub_ = it_->subscribe("thermal/human_mask", queue, &CalibrationNode::onMask, this);
  clusters_sub_ = nh_.subscribe("lidar/human_clusters", queue, &CalibrationNode::onClusters, this);

  calibrate_srv_ = private_nh_.advertiseService("calibrate", &CalibrationNode::onCalibrate, this);
  reset_srv_ = private_nh_.advertiseService("reset", &CalibrationNode::onReset, this);
  save_srv_ = private_nh_.advertiseService("save", &CalibrationNode::onSave, this);
  accept_update_srv_ =
      private_nh_.advertiseService("accept_update", &CalibrationNode::onAcceptUpdate, this);
  timer_ = private_nh_.createWallTimer(ros::WallDuration(1.0 / params_.status_rate_hz),
                                       &CalibrationNode::onTimer, this);

  ROS_INFO("calibration_node started: collecting %d pairs from %s, %s, %s (intrinsics from %s)",
           params_.core.pairs_required, image_topic_.c_str(), mask_topic_.c_str(),
           clusters_topic_.c_str(),
           params_.camera_info_file.empty() ? camera_info_topic_.c_str()
                                            : params_.camera_info_file.c_str());
  if (params_.mode == NodeMode::kMonitor) {
    setState(CalibrationStatus::MONITORING, "monitor mode: waiting for frames (and intrinsics)");
    return;
  }
  setState(CalibrationStatus::COLLECTING, "collecting");
  if (builder_ && static_cast<int>(builder_->pairs().size()) >= params_.core.pairs_required) {
    if (params_.initial_from_tf) {
      resumed_fit_waits_for_tf_ = true;
    } else {
      startOptimization("the resumed dataset already holds ~pairs_required pairs");
    }
  }
}

CalibrationNode::~CalibrationNode() {
  if (worker_.busy()) {
    ROS_INFO("stopping the optimization (shutdown)");
    worker_.requestStop();
  }
}

void CalibrationNode::readParameters() {
  // Throws std::invalid_argument: the node does not start.
  params_ = loadNodeParameters(*makeNodeHandleParameterSource(private_nh_));
  for (const auto& key : unknownParameterKeys(nodeParameterKeys(private_nh_), knownParameterKeys())) {
    ROS_WARN("unknown parameter ~%s ignored (typo? see config/default.yaml)", key.c_str());
  }
  std::ostringstream s;
  for (const auto& kv : describeCoreParameters(params_.core)) s << "\n  " << kv.first << ": " << kv.second;
  for (const auto& kv : describeNodeParameters(params_)) s << "\n  " << kv.first << ": " << kv.second;
  ROS_INFO("effective parameters:%s", s.str().c_str());
  fault_throttle_ = FaultThrottle(params_.fault_log_period_s);
  bad_frames_ = BadFrameReporter(params_.fault_log_period_s);
  guard_ = CallbackGuard(params_.fault_log_period_s);
  // The files written later are checked now: a bad path found when the first pair is kept costs
  // the user the drive so far.
  const std::pair<const char*, const std::string*> files[] = {
      {"output_file", &params_.output_file}, {"dataset_bag", &params_.dataset_bag}};
  for (const auto& [key, path] : files) {
    if (path->empty()) continue;
    const std::string why = whyNotWritable(*path);
    if (!why.empty()) {
      throw std::invalid_argument("parameter '" + std::string(key) + "' = " + *path + ": " + why);
    }
  }
}

void CalibrationNode::createBuilder(const CameraModel& camera, const std::string& source) {
  builder_ = std::make_unique<DatasetBuilder>(camera, params_.core.gate, params_.core.motion);
  // Pairing by association (issue 23): the frames the count rule does not keep are held for the
  // fit, as calibrate_bag holds them, and go to the drift watch with the kept pairs.
  builder_->keepAssociationCandidates(
      pairsByAssociation(params_.core.pairing, params_.core.calibration),
      static_cast<std::size_t>(params_.association_max_candidates));
  builder_->keepSkippedFrames(params_.core.pairing.final_round);
  overlay_->setCamera(camera);
  ROS_INFO("camera intrinsics from %s: %s", source.c_str(), camera.describe().c_str());
}

void CalibrationNode::diagnoseFrameIds(NodeDiagnostics::Status& status) const {
  using diagnostic_msgs::DiagnosticStatus;
  const auto conflict = builder_ ? builder_->frameIdConflict() : std::nullopt;
  if (conflict) {
    status.summary(DiagnosticStatus::ERROR,
                   frameIdConflictText(*conflict, builder_->pairs().size()));
    status.add("other camera_frame", conflict->other_camera_frame);
    status.add("other lidar_frame", conflict->other_lidar_frame);
  } else if (!builder_ || builder_->cameraFrame().empty()) {
    status.summary(DiagnosticStatus::OK, "no valid frame yet");
  } else {
    status.summary(DiagnosticStatus::OK, builder_->frameIdsLocked()
                                             ? "locked to the dataset's frame ids"
                                             : "tentative (fewer than 3 pairs kept)");
  }
  if (builder_) {
    status.add("camera_frame", builder_->cameraFrame());
    status.add("lidar_frame", builder_->lidarFrame());
    status.add("pairs_dropped_for_frame_ids", builder_->pairsDroppedForFrameIds());
  }
}

// The rate of each input and of synchronized frames; a topic that stops or never starts is a
// WARN naming it (while collecting: once the result is out, silence is fine).
void CalibrationNode::diagnoseInputs(NodeDiagnostics::Status& status) {
  using diagnostic_msgs::DiagnosticStatus;
  const auto now = InputRates::Clock::now();
  const std::string problem = input_rates_->problem(now);
  if (!problem.empty() && state_ == CalibrationStatus::COLLECTING) {
    status.summary(DiagnosticStatus::WARN, problem);
  } else {
    status.summaryf(DiagnosticStatus::OK, "%.1f synchronized frames/s", input_rates_->frameRateHz(now));
  }
  for (std::size_t i = 0; i < input_rates_->topics().size(); ++i) {
    status.addf(input_rates_->topics()[i] + " rate (Hz)", "%.1f", input_rates_->rateHz(i, now));
    status.add(input_rates_->topics()[i] + " messages", input_rates_->total(i));
  }
  status.addf("synchronized frames/s", "%.1f", input_rates_->frameRateHz(now));
}

void CalibrationNode::diagnoseCalibration(NodeDiagnostics::Status& status) const {
  using diagnostic_msgs::DiagnosticStatus;
  const std::uint8_t level = state_ == CalibrationStatus::FAILED ? DiagnosticStatus::ERROR : DiagnosticStatus::OK;
  status.summary(level, std::string(stateName(state_)) + ": " + state_message_);
  status.add("state", stateName(state_));
  status.add("pairs kept", builder_ ? builder_->pairs().size() : 0);
  status.add("pairs required", params_.core.pairs_required);
  if (builder_ && builder_->keepsAssociationCandidates()) {
    status.add("association candidates", builder_->candidates().size());
    status.add("association candidates dropped (~association_max_candidates)", builder_->candidatesDropped());
    // Issue 24: the frames the skip rule passed over, held for the final round.
    if (builder_->keepsSkippedFrames()) status.add("skipped frames held", builder_->skippedFrames().size());
  }
  if (result_) {
    status.addf("loss (px)", "%.4f", result_->loss);
    status.add("time offset", timeOffsetText(*result_, quality_ ? quality_->uncertainty : std::nullopt));
    status.addf("time offset (ms)", "%.1f", 1000.0 * result_->time_offset_s);
    if (quality_ && quality_->uncertainty && quality_->uncertainty->timed) {
      status.addf("time offset 95% +- (ms)", "%.1f", quality_->uncertainty->time_offset_ms);
    }
  }
  if (quality_) {
    status.add("verdict", toString(quality_->verdict.verdict));
    for (std::size_t i = 0; i < quality_->verdict.reasons.size(); ++i) {
      status.add("verdict reason " + std::to_string(i + 1), quality_->verdict.reasons[i]);
    }
    if (quality_->uncertainty) {
      const auto& u = *quality_->uncertainty;
      status.addf("rotation 95% +- (deg)", "%.3f %.3f %.3f", u.rotation_deg.x(), u.rotation_deg.y(), u.rotation_deg.z());
      status.addf("translation 95% +- (cm)", "%.2f %.2f %.2f", u.translation_cm.x(), u.translation_cm.y(),
                  u.translation_cm.z());
    }
  }
}

void CalibrationNode::reportSilentInputs() {
  if (state_ != CalibrationStatus::COLLECTING) return;
  const std::string problem = input_rates_->problem(InputRates::Clock::now());
  if (problem.empty()) return;
  if (const auto held_back = fault_throttle_.admit("silent inputs " + problem)) {
    ROS_WARN("%s%s", problem.c_str(), fault_throttle_.heldBackText(*held_back).c_str());
  }
}

void CalibrationNode::onTimer(const ros::WallTimerEvent& /*event*/) {
  guard_.run("the status timer", [&] {
    if (auto outcome = worker_.takeOutcome()) handleOutcome(std::move(*outcome));
    if (resumed_fit_waits_for_tf_ && (initialTfInTree() || (ros::WallTime::now() - start_time_).toSec() >= params_.tf_check_wait_s)) {
      resumed_fit_waits_for_tf_ = false;
      startOptimization("the resumed dataset already holds ~pairs_required pairs");
    }
    if (result_ && !result_published_ && tfCheckWaitOver()) publishResult();
    if (result_ && result_published_) watchTf();
    finishWaitingPairs();
    updateDrift();
    logProgress(false);
    reportSilentInputs();
    publishStatus();
    diagnostics_->update();
  });
}

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
