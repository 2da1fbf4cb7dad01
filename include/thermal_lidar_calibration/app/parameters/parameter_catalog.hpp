#pragma once
// Every parameter table of the package, in documentation order: the core table, the person
// detectors' table (read by the detection nodelets and calibrate_bag --detect), then the
// node-only table. A part that adds its own table lists it once in parameter_catalog.cpp;
// the known keys (typo warnings) and the documentation (config/default.yaml, README) follow.

#include "thermal_lidar_calibration/app/parameters/parameter_table.hpp"

#include <string>
#include <vector>

namespace thermal_lidar_calibration {

std::vector<ParameterDoc> allParameterDocs();
// Every key of every table, each once, in documentation order.
const std::vector<std::string>& knownParameterKeys();

}  // namespace thermal_lidar_calibration
