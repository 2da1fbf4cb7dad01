// The parameter table: defaults = Table 1, overrides from YAML, and the error messages.

#include "thermal_lidar_calibration/app/parameters/detection_parameters.hpp"
#include "thermal_lidar_calibration/app/parameters/core_parameters.hpp"
#include "thermal_lidar_calibration/app/parameters/point_time_field.hpp"
#include "thermal_lidar_calibration/app/parameters/node_parameters.hpp"
#include "thermal_lidar_calibration/app/parameters/unknown_parameters.hpp"
#include "thermal_lidar_calibration/app/parameters/parameter_catalog.hpp"

#include "../support/test_files.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <stdexcept>

namespace tlc = thermal_lidar_calibration;
using namespace tlc;

namespace {

std::string yamlFile(const std::string& text) {
  static int counter = 0;
  static const std::string dir = test_support::tempDir("tlc_params_");
  const std::string path = dir + "/p" + std::to_string(counter++) + ".yaml";
  std::ofstream(path) << text;
  return path;
}

CoreParameters loadText(const std::string& text) {
  return loadCoreParameters(*makeYamlParameterSource(yamlFile(text)));
}

std::string errorOf(const std::string& text) {
  try {
    loadText(text);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "<no exception>";
}

}  // namespace

TEST(Parameters, DefaultsAreTable1) {
  const CoreParameters p = loadText("");
  const auto& c = p.calibration;
  EXPECT_EQ(c.algorithm, tlc::Algorithm::kOutlierRejection);
  EXPECT_EQ(c.refine.mode, tlc::RefineMode::kLocal);
  EXPECT_EQ(c.evolution.population_size, 500);
  EXPECT_EQ(c.evolution.max_iterations, 400);
  EXPECT_DOUBLE_EQ(c.evolution.rotation_interval_rad, 3.5);
  EXPECT_DOUBLE_EQ(c.evolution.translation_interval_m, 1.0);
  EXPECT_DOUBLE_EQ(c.evolution.elite_fraction, 0.15);
  EXPECT_DOUBLE_EQ(c.evolution.crossover_fraction, 0.40);
  EXPECT_EQ(c.evolution.initial_population_factor, 5);
  EXPECT_DOUBLE_EQ(c.evolution.sigma_rot_rad, 0.02);
  EXPECT_DOUBLE_EQ(c.evolution.sigma_trans_m, 0.02);
  EXPECT_DOUBLE_EQ(c.evolution.min_inside_fraction, 0.5);
  EXPECT_DOUBLE_EQ(c.behind_camera_penalty_c1, 5.0);
  EXPECT_EQ(c.outlier.min_sample_large, 20);
  EXPECT_EQ(c.outlier.min_sample_small, 15);
  EXPECT_EQ(c.outlier.min_sample_switch, 40);
  EXPECT_EQ(c.outlier.iterations, 2);
  EXPECT_DOUBLE_EQ(c.outlier.ratio_solution, 0.7);
  EXPECT_DOUBLE_EQ(c.outlier.threshold_px, 2.0);
  EXPECT_EQ(p.gate.max_people, 3);
  EXPECT_EQ(p.gate.skip_frames, 3);
  EXPECT_DOUBLE_EQ(p.sync_slop_s, 0.05);
  EXPECT_EQ(p.sync_queue_size, 30);
  EXPECT_EQ(p.pairs_required, 60);
}

TEST(Parameters, ShippedDefaultYamlMatchesTheStructsAndListsEveryKey) {
  const std::string path = "../config/default.yaml";
  const CoreParameters from_file = loadCoreParameters(*makeYamlParameterSource(path));
  EXPECT_EQ(describeCoreParameters(from_file), describeCoreParameters(CoreParameters{}));
  const std::vector<std::string> keys = yamlFileKeys(path);
  for (const std::string& key : knownParameterKeys()) {
    EXPECT_NE(std::find(keys.begin(), keys.end(), key), keys.end()) << key << " not documented";
  }
  EXPECT_TRUE(unknownParameterKeys(keys, knownParameterKeys()).empty());
}

TEST(Parameters, RigOverlays) {
  const CoreParameters ms2 = loadCoreParameters(*makeYamlParameterSource("../config/ms2.yaml"));
  EXPECT_DOUBLE_EQ(ms2.calibration.outlier.threshold_px, 1.5);
  const CoreParameters fs =
      loadCoreParameters(*makeYamlParameterSource("../config/fieldsafe.yaml"));
  EXPECT_DOUBLE_EQ(fs.calibration.outlier.threshold_px, 2.0);
}

TEST(Parameters, OverridesEveryType) {
  const CoreParameters p = loadText(
      "algorithm: 1\nrefine: none\nseed: 42\npopulation_size: 50\nsigma_rot_rad: 0.05\n"
      "sync_slop: 0.1\nskip_frames: 0\nthreshold_sample_px: 3\n");
  EXPECT_EQ(p.calibration.algorithm, tlc::Algorithm::kPlain);
  EXPECT_EQ(p.calibration.refine.mode, tlc::RefineMode::kNone);
  EXPECT_EQ(p.calibration.seed, 42u);
  EXPECT_EQ(p.calibration.evolution.population_size, 50);
  EXPECT_DOUBLE_EQ(p.calibration.evolution.sigma_rot_rad, 0.05);
  EXPECT_DOUBLE_EQ(p.sync_slop_s, 0.1);
  EXPECT_EQ(p.gate.skip_frames, 0);
  EXPECT_DOUBLE_EQ(p.calibration.outlier.threshold_px, 3.0);  // an integer is a fine double
}

TEST(Parameters, BadValuesNameKeyValueAndRange) {
  EXPECT_EQ(errorOf("population_size: -3\n"),
            "parameter 'population_size' = -3: must be an integer in [2, 100000]");
  EXPECT_EQ(errorOf("population_size: 1.5\n"),
            "parameter 'population_size' = 1.5: must be an integer in [2, 100000]");
  EXPECT_EQ(errorOf("elite_fraction: 1.5\n"),
            "parameter 'elite_fraction' = 1.5: must be a number in [0, 1]");
  EXPECT_EQ(errorOf("sync_slop: 0\n"), "parameter 'sync_slop' = 0: must be a number in (0, 10]");
  EXPECT_EQ(errorOf("refine: global\n"),
            "parameter 'refine' = 'global': must be 'none' or 'local'");
  EXPECT_EQ(errorOf("algorithm: 3\n"),
            "parameter 'algorithm' = 3: must be 1 (plain evolution) or 2 (with outlier rejection)");
  EXPECT_EQ(errorOf("max_people: abc\n"),
            "parameter 'max_people' = 'abc': must be an integer in [1, 1000]");
  EXPECT_EQ(errorOf("threshold_sample_px: .nan\n").rfind("parameter 'threshold_sample_px' = ", 0),
            0u);
  // Cross-key rules come from the core's validate().
  EXPECT_NE(errorOf("elite_fraction: 0.7\ncrossover_fraction: 0.7\n").find("must not exceed 1"),
            std::string::npos);
}

// Issue 21: which field holds the clusters' per-point times.
TEST(Parameters, PointTimeFieldIsAutoNoneOrAFieldName) {
  EXPECT_EQ(loadText("seed: 1\n").point_time_field, "auto");
  EXPECT_EQ(loadText("point_time_field: none\n").point_time_field, "none");
  EXPECT_EQ(loadText("point_time_field: offset_time\n").point_time_field, "offset_time");
  EXPECT_EQ(loadText("point_time_field: t\n").point_time_field, "t");
  EXPECT_EQ(errorOf("point_time_field: \"time stamp\"\n"),
            "parameter 'point_time_field' = 'time stamp': must be auto, none or the name of a PointCloud2 "
            "field (letters, digits, _)");
  EXPECT_EQ(errorOf("point_time_field: \"\"\n"),
            "parameter 'point_time_field' = '': must be auto, none or the name of a PointCloud2 field");
  const tlc::PointTimeField named = tlc::PointTimeField::parse("timestamp");
  EXPECT_EQ(named.mode, tlc::PointTimeField::Mode::kNamed);
  EXPECT_EQ(named.name, "timestamp");
  EXPECT_EQ(tlc::PointTimeField::parse("auto").mode, tlc::PointTimeField::Mode::kAuto);
  EXPECT_EQ(tlc::PointTimeField::parse("none").mode, tlc::PointTimeField::Mode::kNone);
}

TEST(Parameters, BadFiles) {
  EXPECT_THROW(makeYamlParameterSource("/nonexistent/params.yaml"), std::invalid_argument);
  EXPECT_THROW(makeYamlParameterSource(yamlFile("a: [1,\n")), std::invalid_argument);
  EXPECT_THROW(makeYamlParameterSource(yamlFile("- 1\n- 2\n")), std::invalid_argument);
}

TEST(Parameters, UnknownKeysAreReported) {
  const auto keys = yamlFileKeys(yamlFile("populaton_size: 5\nseed: 2\noutput_file: x.yaml\n"));
  EXPECT_EQ(unknownParameterKeys(keys, knownParameterKeys()), std::vector<std::string>{"populaton_size"});
  // Unknown keys are ignored by the loader.
  EXPECT_EQ(loadText("populaton_size: 5\n").calibration.evolution.population_size, 500);
}

// The verdict's thresholds are checked across keys too: a usable bound tighter than the good one
// is refused with both names.
TEST(Parameters, QualityThresholdsAreValidatedAcrossKeys) {
  EXPECT_EQ(loadText("uncertainty_resamples: 200\n").quality.uncertainty.resamples, 200);
  EXPECT_FALSE(loadText("uncertainty: false\n").quality.uncertainty_enabled);
  try {
    loadText("quality_good_rotation_deg: 0.5\nquality_usable_rotation_deg: 0.2\n");
    FAIL() << "usable tighter than good was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("quality_usable_rotation_deg"), std::string::npos) << e.what();
  }
  try {
    loadText("uncertainty_resamples: 10\n");
    FAIL() << "10 resamples were accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("uncertainty_resamples"), std::string::npos) << e.what();
  }
  // The drift candidate's intervals: 0 turns them off, one resample is no interval.
  EXPECT_EQ(loadText("monitor_update_uncertainty_resamples: 0\n").drift.update_uncertainty_resamples, 0);
  try {
    loadText("monitor_update_uncertainty_resamples: 1\n");
    FAIL() << "1 resample was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("monitor_update_uncertainty_resamples"), std::string::npos)
        << e.what();
  }
}

TEST(Parameters, DescribeListsEveryCoreKeyOnce) {
  const auto described = describeCoreParameters(CoreParameters{});
  EXPECT_EQ(described.size(), 98u);  // 35 of the method and gating, 17 quality (issue 8), 16 drift (9),
                                     // 18 timing (21: 16 of the estimate and verdict, 2 of the watch),
                                     // 7 association (23), 2 of the sub-pixel loss (24: refine_outline_px,
                                     // refine_ring_end_weight), refine_evolution_generations,
                                     // association_final_round (24), refine_evolution_min_share
  for (const auto& kv : described) {
    const auto& known = knownParameterKeys();
    EXPECT_NE(std::find(known.begin(), known.end(), kv.first), known.end()) << kv.first;
  }
}

TEST(Parameters, KnownKeysAreTheDescribedKeysEachOnce) {
  std::vector<std::string> described;
  for (const auto& kv : describeCoreParameters(CoreParameters{})) described.push_back(kv.first);
  for (const auto& kv : describeDetectionParameters(DetectionParameters{})) described.push_back(kv.first);
  for (const auto& kv : describeNodeParameters(NodeParameters{})) described.push_back(kv.first);
  EXPECT_EQ(knownParameterKeys(), described);
  std::vector<std::string> sorted = knownParameterKeys();
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(std::adjacent_find(sorted.begin(), sorted.end()), sorted.end());
}

// ---- the node-only table and its cross-key rules ---------------------------------------------

namespace {

NodeParameters loadNodeText(const std::string& text) {
  return loadNodeParameters(*makeYamlParameterSource(yamlFile(text)));
}

std::string nodeErrorOf(const std::string& text) {
  try {
    loadNodeText(text);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "<no exception>";
}

std::string described(const std::vector<std::pair<std::string, std::string>>& kv,
                      const std::string& key) {
  for (const auto& p : kv) {
    if (p.first == key) return p.second;
  }
  return "<missing>";
}

}  // namespace

TEST(NodeParameters, DefaultsAndOverrides) {
  const NodeParameters d = loadNodeText("");
  EXPECT_EQ(d.output_file, "thermal_lidar_calibration.yaml");
  EXPECT_EQ(d.dataset_bag, "thermal_lidar_dataset.bag");
  EXPECT_FALSE(d.resume);
  EXPECT_EQ(d.min_pairs_to_calibrate, 20);
  EXPECT_DOUBLE_EQ(d.status_rate_hz, 2.0);
  const NodeParameters p = loadNodeText(
      "output_file: /tmp/r.yaml\ndataset_bag: ''\nchild_frame: cam_cal\nstatus_rate_hz: 5\n"
      "overlay_max_points: 100\npopulation_size: 50\n");
  EXPECT_EQ(p.output_file, "/tmp/r.yaml");
  EXPECT_EQ(p.dataset_bag, "");
  EXPECT_EQ(p.child_frame, "cam_cal");
  EXPECT_DOUBLE_EQ(p.status_rate_hz, 5.0);
  EXPECT_EQ(p.overlay_max_points, 100);
  EXPECT_EQ(p.core.calibration.evolution.population_size, 50);  // core keys through the same source
}

TEST(NodeParameters, BadValuesAndCrossKeyRules) {
  EXPECT_EQ(nodeErrorOf("output_file: ''\n"),
            "parameter 'output_file' = '': must name the result YAML file");
  EXPECT_EQ(nodeErrorOf("status_rate_hz: 0.05\n"),
            "parameter 'status_rate_hz' = 0.05: must be a number in [0.1, 100]");
  EXPECT_EQ(nodeErrorOf("resume: maybe\n"), "parameter 'resume' = 'maybe': must be true or false");
  EXPECT_EQ(nodeErrorOf("resume: true\ndataset_bag: ''\n"),
            "parameter 'resume' = true but 'dataset_bag' is empty: name the dataset bag to resume");
  // min_pairs_to_calibrate may not exceed pairs_required; its default shrinks to it.
  EXPECT_EQ(nodeErrorOf("pairs_required: 10\nmin_pairs_to_calibrate: 11\n"),
            "parameter 'min_pairs_to_calibrate' = 11: must be an integer in [1, 10]");
  EXPECT_EQ(loadNodeText("pairs_required: 10\n").min_pairs_to_calibrate, 10);
  // Issue 23: one place where association starts, the bound at least one candidate.
  EXPECT_EQ(nodeErrorOf("initial_from_tf: true\ninitial_extrinsic_file: /tmp/start.yaml\n"),
            "parameters 'initial_from_tf' = true and 'initial_extrinsic_file' = /tmp/start.yaml both name where "
            "association starts: set one");
  EXPECT_TRUE(loadNodeText("initial_from_tf: true\n").initial_from_tf);
  EXPECT_FALSE(loadNodeText("").initial_from_tf);
  EXPECT_EQ(nodeErrorOf("association_max_candidates: 0\n"),
            "parameter 'association_max_candidates' = 0: must be an integer in [1, 1000000]");
  // A core key's error comes first, from the core table.
  EXPECT_EQ(nodeErrorOf("population_size: 1\n"),
            "parameter 'population_size' = 1: must be an integer in [2, 100000]");
}

TEST(NodeParameters, DescribeSaysWhatAnEmptyStringMeans) {
  const auto d = describeNodeParameters(loadNodeText("dataset_bag: ''\n"));
  EXPECT_EQ(described(d, "dataset_bag"), "'' (not recorded)");
  EXPECT_EQ(described(d, "child_frame"), "'' (<camera_frame>_calibrated)");
  EXPECT_EQ(described(d, "output_file"), "thermal_lidar_calibration.yaml");
  EXPECT_EQ(described(d, "tf_check_wait_s"), "2");
}
