#pragma once
// The parameters both executables use (optimizer, gating, pairing): calibration_node reads them
// as private parameters (~key), calibrate_bag from its --config YAML (the format of
// config/default.yaml). Their rows: src/app/parameters/core_parameter_table.cpp.

#include "thermal_lidar_calibration/app/parameters/parameter_table.hpp"
#include "thermal_lidar_calibration/core/association_refit.hpp"
#include "thermal_lidar_calibration/core/calibration_config.hpp"
#include "thermal_lidar_calibration/core/drift_config.hpp"
#include "thermal_lidar_calibration/core/frame_gate.hpp"
#include "thermal_lidar_calibration/core/person_motion.hpp"
#include "thermal_lidar_calibration/core/quality_assessment.hpp"

#include <string>
#include <utility>
#include <vector>

namespace thermal_lidar_calibration {

// The member initialisers (here and in the core config structs) are the defaults.
struct CoreParameters {
  CalibrationConfig calibration;
  GateConfig gate;
  double sync_slop_s = 0.05;   // ApproximateTime max interval between image, mask, clusters
  int sync_queue_size = 30;    // ApproximateTime queue per topic
  int pairs_required = 60;     // node: pairs to collect before optimizing
  QualityConfig quality;       // uncertainty, coverage and verdict after a fit (issue 8)
  MotionConfig motion;         // people's motion from neighbouring scans (issue 21)
  DriftConfig drift;           // the drift watch (issue 9): calibrate_bag --monitor, node monitor
  // Issue 21: the clusters' per-point time field: auto, none or a field name (PointTimeField).
  std::string point_time_field = "auto";
  // Issue 23: pairing by association after the first fit, and where it may start instead.
  PairingConfig pairing;
  std::string initial_extrinsic_file;  // a result YAML; empty: the paper's first fit
};

// Its rows (core_parameter_table.cpp) and the rules across keys that follow them; with these,
// parameterTable<>, loadParameters<> and describeParameters (parameter_table.hpp) serve this
// struct, and the named forms below are theirs.
template <>
ParameterTable<CoreParameters> makeParameterTable();
template <>
void finishLoading(const ParameterSource& source, CoreParameters& params);

inline const ParameterTable<CoreParameters>& coreParameterTable() {
  return parameterTable<CoreParameters>();
}
// The defaults overridden by what `source` has, then the core's cross-key rules. Throws
// std::invalid_argument("parameter 'population_size' = -3: must be an integer in [2, 100000]").
inline CoreParameters loadCoreParameters(const ParameterSource& source) {
  return loadParameters<CoreParameters>(source);
}
// Every core key with its effective value (start-up log, result file), in table order.
inline std::vector<std::pair<std::string, std::string>> describeCoreParameters(const CoreParameters& p) {
  return describeParameters(p);
}

}  // namespace thermal_lidar_calibration
