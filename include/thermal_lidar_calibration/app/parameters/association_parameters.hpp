#pragma once
// Issue 23: the keys of pairing by association (core/association_refit.hpp), rows of the core
// parameter table (core_parameter_table.cpp calls addAssociationRows in the gating section).

#include "thermal_lidar_calibration/app/parameters/core_parameters.hpp"

#include <optional>

namespace thermal_lidar_calibration {

void addAssociationRows(ParameterTable<CoreParameters>& t);

// The association the parameters ask for, with the gate's say in it (a matched person needs the
// gate's min_points_per_cluster in view; H_max and the skip rule hold for its pairs). Whether a
// run pairs by association at all: pairsByAssociation(p.pairing, p.calibration).
AssociationPairing associationPairing(const CoreParameters& p);
// The same when the run pairs by association (pairsByAssociation), nullopt when it pairs by
// counts: what a drift watch is given.
std::optional<AssociationPairing> associationIfAsked(const CoreParameters& p);

}  // namespace thermal_lidar_calibration
