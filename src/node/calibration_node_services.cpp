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
  setState(CalibrationStatus::COLLECTING, res.message);
  return true;
}

bool CalibrationNode::onSave(std_srvs::Trigger::Request& /*req*/, std_srvs::Trigger::Response& res) {
  const std::string dataset =
      dataset_writer_ ? "; the dataset bag " + dataset_writer_->path() + " holds every kept pair"
                      : "";
  if (!result_) {
    res.success = false;
    res.message = "no result yet (" + std::string(stateName(state_)) + ", " + progressLine() + ")" +
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
