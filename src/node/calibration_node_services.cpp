// calibration_node: the ~calibrate, ~reset and ~save services (std_srvs/Trigger).

#include "thermal_lidar_calibration/node/calibration_node.hpp"

namespace thermal_lidar_calibration {
namespace ros_io {

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
  if (state_ == CalibrationStatus::OPTIMIZING) {
    worker_.requestStop();
    discard_outcome_ = true;
  }
  if (builder_) builder_->reset();
  stored_stamps_ns_.clear();
  stored_spacing_.reset();
  kept_messages_.clear();
  candidate_messages_.clear();
  last_candidate_recorded_.reset();
  last_skipped_recorded_.reset();
  finished_pairs_ = 0;
  pairs_resumed_ = 0;
  next_fit_pairs_ = 0;
  collecting_quality_.reset();
  collecting_quality_pairs_ = 0;
  result_.reset();
  quality_.reset();
  initial_tf_.reset();  // looked up again at the next fit
  initial_tf_warned_ = false;
  result_published_ = true;
  tf_conflict_.clear();
  overlay_->setEstimate(std::nullopt);
  const std::string bag_note = recorder_->enabled() ? "; " + recorder_->clear() : "";
  res.success = true;
  res.message = "reset: dropped " + std::to_string(n) + " pairs" + bag_note;
  if (drift_) {
    // The watch starts again from the extrinsic now in use, with an empty window.
    const Extrinsic in_use = drift_->snapshot().reference;
    const std::optional<double> time_offset = drift_->snapshot().time_offset_s;
    const std::string origin = drift_reference_;
    const auto seen = drift_->snapshot().pairs_seen;
    drift_.reset();
    res.message += "; drift watch restarted (dropped its " + std::to_string(seen) + " pairs)";
    ROS_INFO("%s", res.message.c_str());
    startMonitoring(in_use, origin, time_offset);
    return true;
  }
  ROS_INFO("%s", res.message.c_str());
  setState(params_.mode == NodeMode::kMonitor ? CalibrationStatus::MONITORING
                                              : CalibrationStatus::COLLECTING,
           res.message);
  return true;
}

// ~save answers only what it checked: success means the result file was written and read back;
// the dataset part is counted from the bag on disk, not from what the writer believes.
bool CalibrationNode::onSave(std_srvs::Trigger::Request& /*req*/, std_srvs::Trigger::Response& res) {
  const std::string on_disk = recorder_->describeOnDisk(builder_ ? builder_->pairs().size() : 0);
  const std::string dataset = on_disk.empty() ? "" : "; " + on_disk;
  if (!result_) {
    res.success = false;
    res.message = "no result to write yet (" + std::string(stateName(state_)) + ", " +
                  progressLine() + ")" + dataset;
    return true;
  }
  const std::string error = writeResult();
  res.success = error.empty();
  res.message = (res.success ? "result written to " + params_.output_file + " and read back"
                             : "result NOT written: " + error) +
                dataset;
  return true;
}

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
