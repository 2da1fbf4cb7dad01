#pragma once
// Issue 23: the keys of pairing by association (core/association_refit.hpp), rows of the core
// parameter table (core_parameter_table.cpp calls addAssociationRows in the gating section).

#include "thermal_lidar_calibration/app/parameters/core_parameters.hpp"

namespace thermal_lidar_calibration {

void addAssociationRows(ParameterTable<CoreParameters>& t);

}  // namespace thermal_lidar_calibration
