// calibration_node's own keys (calibrate_bag ignores them). Adding one: a field in
// NodeParameters (app/parameters/node_parameters.hpp) and one row below; then
// scripts/update_parameter_docs.sh (see src/app/parameters/core_parameter_table.cpp for the row forms).
// Rules across keys go in finishLoading() below.

#include "thermal_lidar_calibration/app/parameters/node_parameters.hpp"

#include <stdexcept>

namespace thermal_lidar_calibration {

template <>
ParameterTable<NodeParameters> makeParameterTable() {
  ParameterTable<NodeParameters> t;
  auto node = t.fields();
  t.section("calibration_node only (calibrate_bag ignores these)");
  node.choice("mode", &NodeParameters::mode,
              {{"calibrate", NodeMode::kCalibrate}, {"monitor", NodeMode::kMonitor}},
              "must be calibrate or monitor",
              "calibrate: collect pairs and optimize; monitor: watch the extrinsic in use for drift "
              "(from reference_file, else the live tf between the two frames)");
  node.choice("stop_when", &NodeParameters::stop_when,
              {{"pairs", StopWhen::kPairs}, {"quality", StopWhen::kQuality}},
              "must be pairs or quality",
              "pairs: optimize once pairs_required pairs are kept; quality: optimize then, and again "
              "every quality_check_every_pairs new pairs until the verdict is good or max_pairs are kept");
  node.integer("quality_check_every_pairs", &NodeParameters::quality_check_every_pairs, {1, 100000}, "",
               "stop_when quality: new pairs between two fits");
  node.integer("max_pairs", &NodeParameters::max_pairs, {1, 100000}, "",
               "stop_when quality: the fit at this many pairs is the last, good or not",
               "at least pairs_required");
  node.boolean("monitor_after_calibration", &NodeParameters::monitor_after_calibration,
               "after a calibration, go on watching its result for drift");
  node.boolean("auto_update", &NodeParameters::auto_update,
               "drift watch: publish and write a confirmed new extrinsic without waiting for "
               "~accept_update");
  node.text("output_file", &NodeParameters::output_file,
            TextRule::required("must name the result YAML file"),
            "result YAML; relative paths are under ROS_HOME");
  node.text("dataset_bag", &NodeParameters::dataset_bag, TextRule::optional("not recorded"),
            "bag recording every kept pair and association candidate");
  node.boolean("resume", &NodeParameters::resume,
               "reload dataset_bag at start and continue collecting", "needs dataset_bag");
  node.text("camera_info_file", &NodeParameters::camera_info_file,
            TextRule::optional("use the topic thermal/camera_info"),
            "camera_calibration YAML for intrinsics");
  node.text("reference_file", &NodeParameters::reference_file,
            TextRule::optional("no reference"),
            "result YAML of the calibration in use: the result reports its difference per axis and its loss "
            "on the same pairs");
  node.text("report_dir", &NodeParameters::report_dir, TextRule::optional("no report"),
            "directory for the visual report written after each calibration (overlays, coverage, "
            "convergence, loss per pair, uncertainty, index.html)");
  node.text("child_frame", &NodeParameters::child_frame,
            TextRule::optional("<camera_frame>_calibrated"),
            "frame published when the camera frame already has a parent");
  node.integer("min_pairs_to_calibrate", &NodeParameters::min_pairs_to_calibrate, {1, 100000}, "",
               "~calibrate service refused below this many pairs", "at most pairs_required");
  node.real("progress_log_period_s", &NodeParameters::progress_log_period_s, aboveRange(0, 3600),
            "s", "period of the \"collecting 12/60\" log line");
  node.real("fault_log_period_s", &NodeParameters::fault_log_period_s, aboveRange(0, 3600), "s",
            "period of the fault warnings: one line per kind of fault (bad frames, stamps, NaN "
            "points, silent inputs, failed callbacks) and period, counting those held back");
  node.real("status_rate_hz", &NodeParameters::status_rate_hz, closedRange(0.1, 100), "Hz",
            "~status publish rate");
  node.real("tf_check_wait_s", &NodeParameters::tf_check_wait_s, closedRange(0, 60), "s",
            "listen to /tf and /tf_static this long before publishing");
  node.integer("overlay_max_points", &NodeParameters::overlay_max_points, {100, 10000000}, "",
               "LiDAR points drawn per ~overlay image");
  node.integer("association_max_candidates", &NodeParameters::association_max_candidates, {1, 1000000}, "",
               "pairing association: frames the count rule did not keep but with people in both modalities, "
               "held for the fit to pair person by person; each holds its image and person regions (about "
               "1.3 MB at 640x512, 16 bit: 300 are about 400 MB). When full, every second one held is "
               "dropped and only every second new one kept, so they stay spread over the drive; ~status "
               "counts the drops");
  node.boolean("initial_from_tf", &NodeParameters::initial_from_tf,
               "pairing association: start from the tf between the LiDAR frame and the camera frame (looked up "
               "when the first fit starts, after tf_check_wait_s) instead of the paper's first fit, if the count "
               "rule's pairs agree with it (initial_extrinsic_min_agreement); without that tf, one warning and the "
               "first fit",
               "not with initial_extrinsic_file");
  return t;
}

template <>
void finishLoading(const ParameterSource& source, NodeParameters& p) {
  p.core = loadParameters<CoreParameters>(source);
  // The minimum for ~calibrate cannot exceed what the node collects before optimizing anyway.
  if (p.min_pairs_to_calibrate > p.core.pairs_required) {
    if (source.has("min_pairs_to_calibrate")) {
      throwBadParameter(source, "min_pairs_to_calibrate",
                        "must be an integer in [1, " + std::to_string(p.core.pairs_required) + "]");
    }
    p.min_pairs_to_calibrate = p.core.pairs_required;
  }
  if (p.stop_when == StopWhen::kQuality && p.max_pairs < p.core.pairs_required) {
    throwBadParameter(source, "max_pairs",
                      "must be at least pairs_required (" + std::to_string(p.core.pairs_required) +
                          ") with stop_when quality");
  }
  if (p.initial_from_tf && !p.core.initial_extrinsic_file.empty()) {
    throw std::invalid_argument("parameters 'initial_from_tf' = true and 'initial_extrinsic_file' = " +
                                p.core.initial_extrinsic_file + " both name where association starts: set one");
  }
  if (p.resume && p.dataset_bag.empty()) {
    throw std::invalid_argument(
        "parameter 'resume' = true but 'dataset_bag' is empty: name the dataset bag to resume");
  }
}

}  // namespace thermal_lidar_calibration
