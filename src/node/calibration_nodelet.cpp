// The calibration as a nodelet (thermal_lidar_calibration/CalibrationNodelet): the same
// CalibrationNode as the executable, so it can join the detectors' nodelet manager and take
// their images and clouds without copies. Same topics, parameters and services.

#include "thermal_lidar_calibration/node/calibration_node.hpp"

#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>

#include <memory>

namespace thermal_lidar_calibration {
namespace ros_io {

class CalibrationNodelet : public nodelet::Nodelet {
 private:
  void onInit() override {
    // The single-threaded handles: CalibrationNode's callbacks must not run concurrently.
    try {
      node_ = std::make_unique<CalibrationNode>(getNodeHandle(), getPrivateNodeHandle());
    } catch (const std::exception& e) {
      // A nodelet cannot end its manager's process: it says why and stays idle.
      NODELET_FATAL("calibration nodelet cannot start: %s", e.what());
    }
  }

  std::unique_ptr<CalibrationNode> node_;
};

}  // namespace ros_io
}  // namespace thermal_lidar_calibration

PLUGINLIB_EXPORT_CLASS(thermal_lidar_calibration::ros_io::CalibrationNodelet, nodelet::Nodelet)
