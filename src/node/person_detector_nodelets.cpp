// thermal_lidar_calibration/ThermalPersonSegmenterNodelet and .../LidarPersonDetectorNodelet:
// the detector nodes in a nodelet manager (with CalibrationNodelet, images and clouds pass
// without copies). Same topics and parameters as the executables.

#include "thermal_lidar_calibration/node/person_detector_nodes.hpp"

#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>

#include <memory>

namespace thermal_lidar_calibration {
namespace ros_io {

template <typename Node>
class DetectorNodelet : public nodelet::Nodelet {
 private:
  void onInit() override {
    try {
      node_ = std::make_unique<Node>(getNodeHandle(), getPrivateNodeHandle());
    } catch (const std::exception& e) {
      NODELET_FATAL("%s cannot start: %s", getName().c_str(), e.what());  // stays idle
    }
  }
  std::unique_ptr<Node> node_;
};

using ThermalPersonSegmenterNodelet = DetectorNodelet<ThermalPersonSegmenterNode>;
using LidarPersonDetectorNodelet = DetectorNodelet<LidarPersonDetectorNode>;

}  // namespace ros_io
}  // namespace thermal_lidar_calibration

PLUGINLIB_EXPORT_CLASS(thermal_lidar_calibration::ros_io::ThermalPersonSegmenterNodelet, nodelet::Nodelet)
PLUGINLIB_EXPORT_CLASS(thermal_lidar_calibration::ros_io::LidarPersonDetectorNodelet, nodelet::Nodelet)
