// NodeDiagnostics: the node's diagnostic_updater.

#include "thermal_lidar_calibration/node/node_diagnostics.hpp"

#include <ros/this_node.h>

namespace thermal_lidar_calibration {
namespace ros_io {

NodeDiagnostics::NodeDiagnostics(const ros::NodeHandle& nh, const ros::NodeHandle& private_nh)
    : updater_(nh, private_nh, ros::this_node::getName()) {
  updater_.setHardwareID("none");  // until the frames are known
}

void NodeDiagnostics::add(const std::string& name, Task task) {
  updater_.add(name, std::move(task));
}

void NodeDiagnostics::setHardwareId(const std::string& id) { updater_.setHardwareID(id); }

void NodeDiagnostics::update() { updater_.update(); }

void NodeDiagnostics::publishNow() { updater_.force_update(); }

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
