#pragma once
// The node's result file after the drift watch replaced the extrinsic (~auto_update or
// ~accept_update): the result keys of the extrinsic now in use, and its history, oldest first:
//   drift_updates:
//     - accepted_by: auto_update | accept_update
//       wall_time: 1795586954.5        # when it was accepted (s since the epoch)
//       change_stamp: 1600000061.0     # data time of the first pair after the change
//       confirmed_stamp: 1600000079.9  # data time of the test that confirmed it
//       old: {rotation_vector, translation}
//       new: {rotation_vector, translation}
//       rotation_change_deg, rotation_change_axes_deg, translation_change_cm,
//       loss_reference, loss_fit, pairs, pairs_used, p_value, complete
// ROS-free.

#include "thermal_lidar_calibration/core/drift_monitor.hpp"

#include <string>
#include <vector>

namespace thermal_lidar_calibration {

struct DriftUpdateEntry {
  DriftUpdate update;
  std::string accepted_by;  // "auto_update" or "accept_update"
  double wall_time_s = 0.0;
};

// Writes `path` (through "<path>.tmp" and a rename) and reads it back; throws std::runtime_error
// naming the file when it does not then hold `history.back()`'s new extrinsic.
void writeDriftUpdateFile(const std::string& path, const std::string& lidar_frame,
                          const std::string& camera_frame,
                          const std::vector<DriftUpdateEntry>& history);

}  // namespace thermal_lidar_calibration
