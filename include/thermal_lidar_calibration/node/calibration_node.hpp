#pragma once
// calibration_node: collects (thermal mask, LiDAR person clusters) pairs through the shared
// ingest path (FrameSynchronizer -> DatasetBuilder, as calibrate_bag), records each kept pair to
// ~dataset_bag, runs calibrate() on a CalibrationWorker when ~pairs_required pairs are kept or on
// ~calibrate, then publishes the static transform, writes ~output_file and draws ~overlay.
// Callbacks only decode and gate; the optimizer runs on the worker thread.

#include "thermal_lidar_calibration/core/calibrator.hpp"
#include "thermal_lidar_calibration/core/dataset_builder.hpp"
#include "thermal_lidar_calibration/core/stored_pair_spacing.hpp"
#include "thermal_lidar_calibration/ros/calibrated_tf_publisher.hpp"
#include "thermal_lidar_calibration/node/calibration_worker.hpp"
#include "thermal_lidar_calibration/node/drift_update_file.hpp"
#include "thermal_lidar_calibration/node/drift_watch_worker.hpp"
#include "thermal_lidar_calibration/ros/dataset_bag.hpp"
#include "thermal_lidar_calibration/app/runtime/bad_frame_reporter.hpp"
#include "thermal_lidar_calibration/app/runtime/fault_throttle.hpp"
#include "thermal_lidar_calibration/node/input_rates.hpp"
#include "thermal_lidar_calibration/node/callback_guard.hpp"
#include "thermal_lidar_calibration/node/dataset_recorder.hpp"
#include "thermal_lidar_calibration/node/node_diagnostics.hpp"
#include "thermal_lidar_calibration/ros/frame_synchronizer.hpp"
#include "thermal_lidar_calibration/app/parameters/node_parameters.hpp"
#include "thermal_lidar_calibration/node/overlay_publisher.hpp"

#include <thermal_lidar_calibration/CalibrationStatus.h>

#include <image_transport/image_transport.h>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <std_srvs/Trigger.h>

#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>

namespace thermal_lidar_calibration {
namespace ros_io {

// The state names of CalibrationStatus::state (COLLECTING, OPTIMIZING, DONE, FAILED).
const char* stateName(std::uint8_t state);

// The frame-id conflict in words, with both ids and the remedy (for ~status, /diagnostics, log).
std::string frameIdConflictText(const FrameIdConflict& conflict, std::size_t pairs);

// One class for the executable (calibration_node) and the nodelet (CalibrationNodelet). Its
// member functions live in one file per responsibility:
//   calibration_node.cpp           construction: parameters, subscriptions, services, timer
//   calibration_node_ingest.cpp    intrinsics, the synchronized frames, the dataset (~resume)
//   calibration_node_result.cpp    the optimization run and its result (tf, file, overlay)
//   calibration_node_services.cpp  ~calibrate, ~reset, ~save
//   calibration_node_status.cpp    state, ~status and the progress log
//   calibration_node_monitor.cpp   the drift watch (~mode: monitor), ~accept_update
class CalibrationNode {
 public:
  // Reads the parameters of `private_nh` (throws std::invalid_argument on a bad one), reloads
  // the dataset with ~resume, then subscribes the inputs on `nh` (remap them) and advertises
  // ~status, ~overlay and the services on `private_nh`. Callbacks run on the handles'
  // callback queue: one thread at a time (the nodelet passes its single-threaded handles).
  CalibrationNode(ros::NodeHandle nh, ros::NodeHandle private_nh);
  ~CalibrationNode();

 private:
  // A kept pair waits for the scans after it (its people's motion); when none come for this long
  // (a replay ended, the LiDAR stopped) it is finished with the scans there are.
  static constexpr double kScanSilenceS = 1.0;

  // calibration_node.cpp
  void readParameters();
  void createBuilder(const CameraModel& camera, const std::string& source);
  void onTimer(const ros::WallTimerEvent& event);
  void diagnoseFrameIds(NodeDiagnostics::Status& status) const;
  void diagnoseInputs(NodeDiagnostics::Status& status);
  void diagnoseCalibration(NodeDiagnostics::Status& status) const;
  void reportSilentInputs();

  // calibration_node_ingest.cpp (callbacks, main thread)
  void resumeDataset();
  void onImage(const sensor_msgs::Image::ConstPtr& msg);
  void onMask(const sensor_msgs::Image::ConstPtr& msg);
  void onClusters(const sensor_msgs::PointCloud2::ConstPtr& msg);
  void observeScan(const sensor_msgs::PointCloud2& clusters);  // issue 21: people's motion
  void handleFinishedPairs();  // pairs with their motion: the dataset bag, the fit, the drift watch
  void recordHeldCandidates();  // association candidates the builder holds: into the dataset bag
  struct KeptMessages;
  void record(const KeptMessages& kept, const CalibrationPair& pair, const StoredFrameKind& kind);
  void finishWaitingPairs();   // timer: no scan for kScanSilenceS finishes the waiting pairs
  void reportSyncFault(const std::string& topic, const FrameSynchronizer::AddOutcome& outcome);
  void reportFrameIdConflict();
  void noteInput(std::size_t topic);  // 0 image, 1 mask, 2 clusters (input_rates_'s order)
  void onCameraInfo(const sensor_msgs::CameraInfo::ConstPtr& msg);
  void onFrame(const sensor_msgs::Image::ConstPtr& image, const sensor_msgs::Image::ConstPtr& mask,
               const sensor_msgs::PointCloud2::ConstPtr& clusters);

  // calibration_node_result.cpp
  std::string startOptimization(const std::string& why);  // "" when started, else the refusal
  std::optional<JobReference> runReference() const;  // the calibration in use, if known
  // Where association starts (issue 23): ~initial_extrinsic_file, else with ~initial_from_tf the
  // tf between the two frames (looked up once found, never this node's own result); nullopt:
  // the paper's first fit.
  std::optional<InitialExtrinsic> initialExtrinsic();
  // Pairs at which the next fit starts by itself: ~pairs_required, then with ~stop_when quality
  // quality_check_every_pairs more after each fit whose verdict was not good.
  std::size_t nextFitPairs() const;
  void handleOutcome(CalibrationWorker::Outcome outcome);
  void publishResult();
  // ~save: writes ~output_file again and reads it back; "" when the file holds the result.
  std::string writeResult();
  // The tf check's wait is over: ~tf_check_wait_s of wall time since start AND of the data's
  // own time (ros::Time, sim time on a replay) since the first input message, so a resumed node
  // does not publish before a replayed bag's /tf_static has had its chance.
  bool tfCheckWaitOver() const;
  // After publishing: a parent for the camera frame found later moves the result to the
  // fallback frame, loudly.
  void watchTf();
  void diagnoseTf(NodeDiagnostics::Status& status) const;

  // calibration_node_services.cpp
  bool onCalibrate(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);
  bool onReset(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);
  bool onSave(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);

  // calibration_node_monitor.cpp
  // `time_offset_s`: the camera time offset the reference goes with (issue 21), if known.
  void startMonitoring(const Extrinsic& reference, const std::string& origin,
                       std::optional<double> time_offset_s);
  // The time offset a reference from elsewhere goes with: ~time_offset_s when fixed, else none.
  std::optional<double> configuredTimeOffset() const;
  bool ensureMonitoring(const std::string& camera_frame, const std::string& lidar_frame);
  void monitorKeptPairs();
  void updateDrift();  // timer: state changes, ~auto_update
  std::string acceptDriftUpdate(const std::string& by);  // what happened, "refused: ..." if not
  bool onAcceptUpdate(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);
  void fillDriftStatus(CalibrationStatus& msg) const;
  void diagnoseDrift(NodeDiagnostics::Status& status) const;

  // calibration_node_status.cpp
  void setState(std::uint8_t state, const std::string& message);  // CalibrationStatus::*
  void logProgress(bool force);
  void publishStatus();
  std::string progressLine() const;

  ros::NodeHandle nh_;          // node namespace: input topics (remap them)
  ros::NodeHandle private_nh_;  // ~ parameters, ~status, ~overlay, services
  NodeParameters params_;
  std::string image_topic_, mask_topic_, clusters_topic_, camera_info_topic_;

  std::unique_ptr<DatasetBuilder> builder_;  // holds the camera model once intrinsics are known
  std::optional<sensor_msgs::CameraInfo> camera_info_msg_;  // written with each pair
  std::unique_ptr<DatasetRecorder> recorder_;  // ~dataset_bag (a failed write stops recording)
  std::unique_ptr<NodeDiagnostics> diagnostics_;  // /diagnostics; parts add their tasks
  std::set<long long> stored_stamps_ns_;  // image stamps of pairs in the dataset (no duplicates)
  // ~resume: live frames within the skip rule of a stored pair are passed over (a drive played
  // again from its start), when the stored pairs' frame numbers give the frame period.
  std::optional<StoredPairSpacing> stored_spacing_;
  // The messages of kept pairs not yet finished (waiting for their later scans), oldest first:
  // recorded to the dataset bag with the motion when the pair is finished.
  struct KeptMessages {
    sensor_msgs::Image::ConstPtr image, mask;
    sensor_msgs::PointCloud2::ConstPtr clusters;
  };
  std::deque<KeptMessages> kept_messages_;
  // The same for frames offered as association candidates, and skipped frames decoded for the
  // final round (issue 24), by frame index: recorded when the builder holds them (its bound may
  // pass some over), forgotten once frames after them are done.
  std::map<std::uint64_t, KeptMessages> candidate_messages_;
  std::optional<std::uint64_t> last_candidate_recorded_;  // frame index (restored ones included)
  std::optional<std::uint64_t> last_skipped_recorded_;    // the same for skipped frames
  std::size_t finished_pairs_ = 0;  // builder pairs already handed on (recorded, fitted, watched)
  ros::WallTime last_scan_time_;
  std::size_t pairs_resumed_ = 0;
  bool frame_id_conflict_ = false;  // frames keep arriving with other ids than the dataset's
  std::unique_ptr<InputRates> input_rates_;  // image, mask, clusters: rates and silent topics
  std::optional<ros::Time> first_input_time_;  // ros::Time::now() at the first input message
  std::string tf_conflict_;  // a second parent found after publishing, in words

  std::unique_ptr<FrameSynchronizer> synchronizer_;
  std::unique_ptr<image_transport::ImageTransport> it_;
  image_transport::Subscriber image_sub_, mask_sub_;
  ros::Subscriber clusters_sub_, camera_info_sub_;
  std::unique_ptr<OverlayPublisher> overlay_;
  std::unique_ptr<CalibratedTfPublisher> tf_publisher_;
  ros::Publisher status_pub_;
  ros::ServiceServer calibrate_srv_, reset_srv_, save_srv_, accept_update_srv_;
  ros::WallTimer timer_;

  CalibrationWorker worker_;
  std::unique_ptr<DriftWatchWorker> drift_;  // while monitoring
  std::string drift_reference_;              // where the watched extrinsic came from, in words
  DriftState last_drift_state_ = DriftState::kOk;
  DriftState last_timing_state_ = DriftState::kOk;
  std::string drift_error_;
  std::vector<DriftUpdateEntry> drift_history_;  // accepted updates, oldest first
  bool discard_outcome_ = false;  // set by ~reset while a run is stopping
  std::size_t next_fit_pairs_ = 0;  // 0: ~pairs_required (stop_when quality raises it)
  // ~stop_when quality while collecting: coverage and verdict of the pairs so far (no fit yet),
  // refreshed every ~quality_check_every_pairs kept pairs.
  std::optional<QualityAssessment> collecting_quality_;
  std::size_t collecting_quality_pairs_ = 0;
  void assessCollection();
  // The latest fit's assessment, else the collection's so far; nullptr when neither exists.
  const QualityAssessment* latestQuality() const;
  std::uint8_t state_ = CalibrationStatus::COLLECTING;
  std::string state_message_;
  std::optional<CalibrationResult> result_;
  std::optional<QualityAssessment> quality_;  // of result_: intervals, coverage, verdict, reference
  ResultContext result_context_;              // what the result file holds besides result_
  std::optional<Extrinsic> reference_;        // ~reference_file
  std::optional<InitialExtrinsic> initial_file_;  // ~initial_extrinsic_file, read at start
  std::optional<InitialExtrinsic> initial_tf_;    // ~initial_from_tf: the tf, once found
  bool initial_tf_warned_ = false;                // its absence was said
  // ~resume with ~initial_from_tf: the resumed dataset's fit waits until the tf between the two
  // frames is in the tree, or the tree has been listened to for ~tf_check_wait_s without it (the
  // timer starts it).
  bool resumed_fit_waits_for_tf_ = false;
  bool initialTfInTree() const;
  std::optional<double> reference_time_offset_s_;  // its camera time offset, if it applied one
  std::string camera_frame_, lidar_frame_;
  std::string published_child_;
  bool result_published_ = true;  // false while a result waits for the tf check window
  ros::WallTime start_time_;
  ros::WallTime last_progress_log_;
  std::uint64_t last_logged_considered_ = ~0ull;
  // One line per kind of fault and ~fault_log_period_s (made again once the parameters are read).
  FaultThrottle fault_throttle_{params_.fault_log_period_s};
  BadFrameReporter bad_frames_{params_.fault_log_period_s};  // the wording calibrate_bag uses too
  CallbackGuard guard_{params_.fault_log_period_s};  // no exception from a callback ends the node
};

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
