#pragma once
// calibration_node's health on /diagnostics (diagnostic_msgs/DiagnosticArray): one
// diagnostic_updater::Updater owned here, and one task per part of the node that knows its own
// state. A part adds its task from its own file, keeping the state and the words together:
//
//   diagnostics.add("dataset recording",
//                   [this](diagnostic_updater::DiagnosticStatusWrapper& s) { recorder_.diagnose(s); });
//
// The status names read "calibration_node: dataset recording". Tasks run on the node's timer
// (at ~diagnostic_period, default 1 s); publishNow() sends at once after a change that must
// not wait (an error).

#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/node_handle.h>

#include <functional>
#include <string>

namespace thermal_lidar_calibration {
namespace ros_io {

class NodeDiagnostics {
 public:
  using Status = diagnostic_updater::DiagnosticStatusWrapper;
  using Task = std::function<void(Status&)>;

  NodeDiagnostics(const ros::NodeHandle& nh, const ros::NodeHandle& private_nh);

  void add(const std::string& name, Task task);
  // The device these diagnostics are about, e.g. "thermal_optical/velodyne".
  void setHardwareId(const std::string& id);
  void update();      // call often; publishes at most once per period
  void publishNow();  // runs every task and publishes now

 private:
  diagnostic_updater::Updater updater_;
};

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
