#pragma once
// The calibrate_bag tool as a function: read the bag through the shared ingest path, calibrate,
// write the result file and print the summary.

#include "thermal_lidar_calibration/tools/calibrate_bag_options.hpp"

namespace thermal_lidar_calibration {
namespace ros_io {

// Returns 0 on success. Throws std::invalid_argument (bad input) or std::runtime_error (could not
// finish) with one line for the user; the caller prints it and exits with 1.
int runCalibrateBag(const CalibrateBagOptions& options);

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
