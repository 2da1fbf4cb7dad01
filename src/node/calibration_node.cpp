// calibration_node: subscriptions, the shared ingest path, the worker, services and the result.

#include "thermal_lidar_calibration/node/calibration_node.hpp"

#include "thermal_lidar_calibration/app/camera_info_file.hpp"
#include "thermal_lidar_calibration/app/static_transform_command.hpp"
#include "thermal_lidar_calibration/ros/msg_conversion.hpp"
#include "thermal_lidar_calibration/ros/node_parameter_source.hpp"
#include "thermal_lidar_calibration/app/result_file.hpp"
#include "thermal_lidar_calibration/app/unknown_parameters.hpp"
#include "thermal_lidar_calibration/node/parameter_catalog.hpp"

#include <unistd.h>

#include <sstream>
#include <stdexcept>

namespace thermal_lidar_calibration {
namespace ros_io {

const char* toString(NodeState state) {
  switch (state) {
    case NodeState::kCollecting: return "collecting";
    case NodeState::kOptimizing: return "optimizing";
    case NodeState::kDone: return "done";
    case NodeState::kFailed: return "failed";
  }
  return "unknown";
}

CalibrationNode::CalibrationNode(ros::NodeHandle private_nh)
    : nh_(), private_nh_(std::move(private_nh)), start_time_(ros::WallTime::now()) {
  readParameters();
  image_topic_ = nh_.resolveName("thermal/image_raw");
  mask_topic_ = nh_.resolveName("thermal/human_mask");
  clusters_topic_ = nh_.resolveName("lidar/human_clusters");
  camera_info_topic_ = nh_.resolveName("thermal/camera_info");

  tf_publisher_ = std::make_unique<CalibratedTfPublisher>(params_.child_frame);
  status_pub_ = private_nh_.advertise<CalibrationStatus>("status", 1, /*latch=*/true);
  overlay_ = std::make_unique<OverlayPublisher>(private_nh_, params_.overlay_max_points,
                                                clusters_topic_);
  if (!params_.camera_info_file.empty()) {
    const CameraModel camera = loadCameraInfoFile(params_.camera_info_file);  // throws
    camera_info_msg_ = cameraInfoFromModel(camera);
    createBuilder(camera, params_.camera_info_file);
  }
  if (!params_.dataset_bag.empty()) {
    if (params_.resume) resumeDataset();
    dataset_writer_ = std::make_unique<DatasetBagWriter>(params_.dataset_bag, params_.resume);
  }
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
  timer_ = private_nh_.createWallTimer(ros::WallDuration(1.0 / params_.status_rate_hz),
                                       &CalibrationNode::onTimer, this);

  ROS_INFO("calibration_node started: collecting %d pairs from %s, %s, %s (intrinsics from %s)",
           params_.core.pairs_required, image_topic_.c_str(), mask_topic_.c_str(),
           clusters_topic_.c_str(),
           params_.camera_info_file.empty() ? camera_info_topic_.c_str()
                                            : params_.camera_info_file.c_str());
  setState(NodeState::kCollecting, "collecting");
  if (builder_ && static_cast<int>(builder_->pairs().size()) >= params_.core.pairs_required) {
    startOptimization("the resumed dataset already holds ~pairs_required pairs");
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
}

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
  for (const auto& error : contents.errors) ROS_WARN("~resume: skipped a stored pair: %s", error.c_str());
  if (!builder_) {
    if (!contents.camera) {
      throw std::runtime_error("~resume: " + params_.dataset_bag +
                               " holds no camera_info; set ~camera_info_file");
    }
    camera_info_msg_ = cameraInfoFromModel(*contents.camera);
    createBuilder(*contents.camera, params_.dataset_bag);
  }
  for (std::size_t i = 0; i < contents.pairs.size(); ++i) {
    // The exact header stamp, as onFrame keys live frames (not ros::Time(pair.stamp_s): a double
    // at epoch times has ~240 ns resolution, so the nanoseconds would not round-trip).
    stored_stamps_ns_.insert(static_cast<long long>(contents.pair_stamps_ns[i]));
    builder_->addExistingPair(std::move(contents.pairs[i]));  // throws if the camera size differs
  }
  pairs_resumed_ = builder_->pairs().size();
  camera_frame_ = contents.camera_frame;
  lidar_frame_ = contents.lidar_frame;
  ROS_INFO("~resume: reloaded %zu pairs from %s", pairs_resumed_, params_.dataset_bag.c_str());
}

void CalibrationNode::createBuilder(const CameraModel& camera, const std::string& source) {
  builder_ = std::make_unique<DatasetBuilder>(camera, params_.core.gate);
  overlay_->setCamera(camera);
  ROS_INFO("camera intrinsics from %s: %s", source.c_str(), camera.describe().c_str());
}

void CalibrationNode::onCameraInfo(const sensor_msgs::CameraInfo::ConstPtr& msg) {
  if (builder_) return;  // intrinsics are cached from the first valid message
  try {
    const CameraModel camera = cameraModelFromMsg(*msg);
    camera_info_msg_ = *msg;
    createBuilder(camera, camera_info_topic_);
    camera_info_sub_.shutdown();
  } catch (const std::invalid_argument& e) {
    ROS_WARN_THROTTLE(5.0, "%s: %s", camera_info_topic_.c_str(), e.what());
  }
}

void CalibrationNode::onImage(const sensor_msgs::Image::ConstPtr& msg) {
  synchronizer_->addImage(msg);
  overlay_->onImage(msg);
}

void CalibrationNode::onMask(const sensor_msgs::Image::ConstPtr& msg) {
  synchronizer_->addMask(msg);
  overlay_->onMask(msg);
}

void CalibrationNode::onClusters(const sensor_msgs::PointCloud2::ConstPtr& msg) {
  synchronizer_->addClusters(msg);
  overlay_->onClusters(msg);
}

void CalibrationNode::onFrame(const sensor_msgs::Image::ConstPtr& image,
                              const sensor_msgs::Image::ConstPtr& mask,
                              const sensor_msgs::PointCloud2::ConstPtr& clusters) {
  if (!builder_) {
    ROS_WARN_THROTTLE(5.0, "no intrinsics yet: waiting for %s (or set ~camera_info_file)",
                      camera_info_topic_.c_str());
    return;
  }
  if (state_ == NodeState::kOptimizing || state_ == NodeState::kDone) return;
  if (stored_stamps_ns_.count(static_cast<long long>(image->header.stamp.toNSec())) != 0) {
    ROS_DEBUG("frame %.3f is already in the dataset", image->header.stamp.toSec());
    return;
  }
  const std::uint64_t nonfinite_before = builder_->counts().nonfinite_points_dropped;
  const OfferOutcome outcome = builder_->offer([&] {
    return decodeFrame(*image, *mask, *clusters, image_topic_, mask_topic_, clusters_topic_);
  });
  const std::uint64_t nonfinite = builder_->counts().nonfinite_points_dropped - nonfinite_before;
  if (nonfinite > 0) {
    ROS_WARN_THROTTLE(kFaultLogPeriodS, "%s: dropped %llu NaN/inf points of the cloud at %.3f (%llu so far)",
                      clusters_topic_.c_str(), static_cast<unsigned long long>(nonfinite),
                      clusters->header.stamp.toSec(),
                      static_cast<unsigned long long>(builder_->counts().nonfinite_points_dropped));
  }
  if (outcome.decision == GateDecision::kBadMessage) {
    // Decoder errors name their topic; size checks against camera_info concern the mask.
    const std::string where =
        outcome.error.find('/') != std::string::npos ? "" : " (" + mask_topic_ + ")";
    if (fault_throttle_.shouldReport(outcome.error)) {  // each kind of fault, throttled
      ROS_WARN("bad frame at %.3f%s: %s (%llu bad so far; repeats of this fault are shown at most "
               "every %.0f s)",
               image->header.stamp.toSec(), where.c_str(), outcome.error.c_str(),
               static_cast<unsigned long long>(builder_->counts()[GateDecision::kBadMessage]),
               kFaultLogPeriodS);
    }
    return;
  }
  if (outcome.decision != GateDecision::kKept) {
    ROS_DEBUG("frame %.3f: %s (mask %d people, clusters %d)", image->header.stamp.toSec(),
              toString(outcome.decision), outcome.mask_people, outcome.cluster_people);
    return;
  }
  stored_stamps_ns_.insert(static_cast<long long>(image->header.stamp.toNSec()));
  camera_frame_ = builder_->cameraFrame();
  lidar_frame_ = builder_->lidarFrame();
  if (dataset_writer_) {
    try {
      dataset_writer_->write(*image, *mask, *clusters, *camera_info_msg_);
    } catch (const std::exception& e) {
      ROS_ERROR_THROTTLE(5.0, "kept pair not recorded: %s", e.what());
    }
  }
  ROS_DEBUG("kept frame %.3f (%d people): %s", image->header.stamp.toSec(), outcome.mask_people,
            progressLine().c_str());
  if (static_cast<int>(builder_->pairs().size()) >= params_.core.pairs_required &&
      state_ == NodeState::kCollecting) {
    startOptimization("~pairs_required reached");
  }
}

std::string CalibrationNode::startOptimization(const std::string& why) {
  if (state_ == NodeState::kOptimizing) return "refused: already optimizing";
  if (worker_.busy()) return "refused: the previous optimization is still stopping; try again";
  if (!builder_) return "refused: no camera intrinsics yet (" + camera_info_topic_ + ")";
  const std::size_t n = builder_->pairs().size();
  if (static_cast<int>(n) < params_.min_pairs_to_calibrate) {
    return "refused: only " + std::to_string(n) + " pairs kept, at least " +
           std::to_string(params_.min_pairs_to_calibrate) + " needed (~min_pairs_to_calibrate)";
  }
  result_stamps_s_.clear();
  for (const auto& pair : builder_->pairs()) result_stamps_s_.push_back(pair.stamp_s);
  discard_outcome_ = false;
  worker_.start(builder_->camera(), builder_->pairs(), params_.core.calibration);
  logProgress(true);
  setState(NodeState::kOptimizing, "optimizing " + std::to_string(n) + " pairs (" + why + ")");
  ROS_INFO("optimizing %zu pairs on a worker thread (%s)", n, why.c_str());
  return "";
}

void CalibrationNode::onTimer(const ros::WallTimerEvent& /*event*/) {
  if (auto outcome = worker_.takeOutcome()) handleOutcome(std::move(*outcome));
  if (result_ && !result_published_ &&
      (ros::WallTime::now() - start_time_).toSec() >= params_.tf_check_wait_s) {
    publishResult();
  }
  logProgress(false);
  publishStatus();
}

void CalibrationNode::handleOutcome(CalibrationWorker::Outcome outcome) {
  if (discard_outcome_) {
    discard_outcome_ = false;
    return;
  }
  if (!outcome.result) {
    ROS_ERROR("calibration failed: %s", outcome.error.c_str());
    setState(NodeState::kFailed, "calibration failed: " + outcome.error);
    return;
  }
  if (outcome.result->stopped) {
    setState(NodeState::kCollecting, "optimization stopped");
    return;
  }
  result_ = std::move(outcome.result);
  writeResult();
  overlay_->setEstimate(result_->extrinsic);
  result_published_ = false;
  if ((ros::WallTime::now() - start_time_).toSec() >= params_.tf_check_wait_s) publishResult();
  setState(NodeState::kDone, "done: loss " + std::to_string(result_->loss) + " px");
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

void CalibrationNode::writeResult() {
  ResultContext context;
  context.lidar_frame = lidar_frame_;
  context.camera_frame = camera_frame_;
  context.source = "live";
  context.pair_stamps_s = result_stamps_s_;
  context.parameters = params_.core;
  try {
    writeResultFile(params_.output_file, *result_, context);
    ROS_INFO("result written to %s", params_.output_file.c_str());
  } catch (const std::exception& e) {
    ROS_ERROR("%s", e.what());
  }
}

bool CalibrationNode::onCalibrate(std_srvs::Trigger::Request& /*req*/,
                                  std_srvs::Trigger::Response& res) {
  const std::string refusal = startOptimization("~calibrate");
  res.success = refusal.empty();
  res.message = res.success ? state_message_ : refusal;
  if (!res.success) ROS_INFO("~calibrate %s", refusal.c_str());
  return true;
}

// ~reset clears the dataset, the dataset bag and the result at once; it does not ask twice.
bool CalibrationNode::onReset(std_srvs::Trigger::Request& /*req*/, std_srvs::Trigger::Response& res) {
  const std::size_t n = builder_ ? builder_->pairs().size() : 0;
  if (state_ == NodeState::kOptimizing) {
    worker_.requestStop();
    discard_outcome_ = true;
  }
  if (builder_) builder_->reset();
  stored_stamps_ns_.clear();
  pairs_resumed_ = 0;
  result_.reset();
  result_published_ = true;
  overlay_->setEstimate(std::nullopt);
  std::string bag_note;
  if (dataset_writer_) {
    try {
      dataset_writer_->clear();
      bag_note = " and deleted " + dataset_writer_->path();
    } catch (const std::exception& e) {
      bag_note = "; " + std::string(e.what());
    }
  }
  res.success = true;
  res.message = "reset: dropped " + std::to_string(n) + " pairs" + bag_note;
  ROS_INFO("%s", res.message.c_str());
  setState(NodeState::kCollecting, res.message);
  return true;
}

bool CalibrationNode::onSave(std_srvs::Trigger::Request& /*req*/, std_srvs::Trigger::Response& res) {
  const std::string dataset =
      dataset_writer_ ? "; the dataset bag " + dataset_writer_->path() + " holds every kept pair"
                      : "";
  if (!result_) {
    res.success = false;
    res.message = "no result yet (" + std::string(toString(state_)) + ", " + progressLine() + ")" +
                  dataset;
    return true;
  }
  writeResult();
  res.success = true;
  res.message = "result written to " + params_.output_file + dataset;
  return true;
}

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
