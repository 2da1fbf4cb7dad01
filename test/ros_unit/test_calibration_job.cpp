// The calibration job both front ends run: fit, quality, truth, result file and report from one
// request; failures come back in the outcome (never as exceptions); a stop keeps the disk clean
// unless the front end asks for its best-so-far.

#include "thermal_lidar_calibration/app/runtime/calibration_job.hpp"

#include "thermal_lidar_calibration/core/loss.hpp"

#include "../support/synthetic_pairs.hpp"
#include "../support/test_files.hpp"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>

using namespace thermal_lidar_calibration;
using test_support::fieldsafeCamera;
using test_support::fieldsafeTruth;

namespace {

constexpr double kDeg = M_PI / 180.0;

// A quick but real job: Algorithm 1 with a small population, refinement, a short bootstrap.
CalibrationJobRequest quickRequest(const std::string& dir) {
  CalibrationJobRequest r;
  r.camera = fieldsafeCamera();
  test_support::SyntheticPairsOptions o;
  o.pairs = 24;
  o.seed = 11;
  r.pairs = test_support::makeSyntheticPairs(r.camera, fieldsafeTruth(), o);
  for (std::size_t i = 0; i < r.pairs.size(); ++i) r.pairs[i].stamp_s = 100.0 + static_cast<double>(i);
  CalibrationConfig& c = r.parameters.calibration;
  c.algorithm = Algorithm::kPlain;
  c.evolution.population_size = 150;
  c.evolution.max_iterations = 80;
  c.seed = 5;
  r.parameters.quality.uncertainty.resamples = 10;
  r.lidar_frame = "velodyne";
  r.camera_frame = "thermal_optical";
  r.source = "unit test";
  r.report_title = "test_calibration_job";
  r.output_file = dir + "/result.yaml";
  r.report_dir = dir + "/report";
  r.truth = JobTruth{fieldsafeTruth(), "truth.yaml"};
  r.reference = JobReference{fieldsafeTruth(), "file", "reference.yaml"};
  return r;
}

}  // namespace

TEST(CalibrationJob, FitsAssessesAndWritesTheResultFileAndReport) {
  const std::string dir = test_support::tempDir("tlc_job_");
  const CalibrationJobRequest request = quickRequest(dir);
  std::vector<JobProgress::Stage> stages;
  const CalibrationJobOutcome out = runCalibrationJob(request, [&](const JobProgress& p) {
    if (stages.empty() || stages.back() != p.stage) stages.push_back(p.stage);
    return true;
  });
  ASSERT_TRUE(out.result) << out.error;
  EXPECT_TRUE(out.error.empty());
  EXPECT_EQ(out.pairs, request.pairs.size());
  EXPECT_LT(rotationErrorRad(out.result->extrinsic, fieldsafeTruth()), 0.3 * kDeg);
  EXPECT_LT(translationErrorM(out.result->extrinsic, fieldsafeTruth()), 0.05);
  // The stages in order, each reported.
  const std::vector<JobProgress::Stage> expected{JobProgress::Stage::kFit, JobProgress::Stage::kUncertainty,
                                                 JobProgress::Stage::kWriting};
  EXPECT_EQ(stages, expected);
  // Quality with the reference named as the request named it.
  ASSERT_TRUE(out.quality);
  ASSERT_TRUE(out.quality->uncertainty);
  EXPECT_EQ(out.quality->uncertainty->resamples, 10);
  ASSERT_TRUE(out.quality->reference);
  EXPECT_EQ(out.quality->reference->source, "file");
  EXPECT_EQ(out.quality->reference->origin, "reference.yaml");
  // Truth comparison in the context, as in the file.
  ASSERT_TRUE(out.context.truth);
  EXPECT_NEAR(out.context.truth->rotation_error_rad, rotationErrorRad(out.result->extrinsic, fieldsafeTruth()), 1e-12);
  const LossEvaluator nearest(request.camera, request.pairs, LossConfig{5.0, PixelRule::kNearest});
  EXPECT_DOUBLE_EQ(out.context.truth->truth_loss, nearest.loss(fieldsafeTruth(), usedPairs(*out.result)));
  ASSERT_EQ(out.context.pair_stamps_s.size(), request.pairs.size());
  EXPECT_DOUBLE_EQ(out.context.pair_stamps_s.back(), 123.0);
  // The file holds the result, the truth block, the quality keys and one row per pair.
  EXPECT_TRUE(out.result_file_written) << out.result_file_error;
  const Extrinsic read = readExtrinsicFile(request.output_file);
  // 1e-7: rotationErrorRad takes an arccosine, which cannot tell angles below ~2e-8 rad from 0.
  EXPECT_LT(rotationErrorRad(read, out.result->extrinsic), 1e-7);
  const YAML::Node yaml = YAML::LoadFile(request.output_file);
  EXPECT_EQ(yaml["lidar_frame"].as<std::string>(), "velodyne");
  EXPECT_EQ(yaml["source"].as<std::string>(), "unit test");
  EXPECT_TRUE(yaml["truth"]);
  EXPECT_TRUE(yaml["verdict"]);
  EXPECT_TRUE(yaml["reference"]);
  EXPECT_EQ(yaml["pairs"].size(), request.pairs.size());
  // The report.
  EXPECT_TRUE(out.report_error.empty()) << out.report_error;
  EXPECT_FALSE(out.report_files.empty());
  EXPECT_TRUE(std::filesystem::exists(request.report_dir + "/index.html"));
}

TEST(CalibrationJob, TheSameRequestGivesTheSameResultWhateverTheThreads) {
  const std::string dir = test_support::tempDir("tlc_job_");
  CalibrationJobRequest request = quickRequest(dir);
  request.output_file.clear();
  request.report_dir.clear();
  request.parameters.calibration.num_threads = 1;
  const CalibrationJobOutcome one = runCalibrationJob(request);
  request.parameters.calibration.num_threads = 2;
  const CalibrationJobOutcome two = runCalibrationJob(request);
  ASSERT_TRUE(one.result && two.result);
  EXPECT_EQ(one.result->extrinsic.rotation_vector, two.result->extrinsic.rotation_vector);
  EXPECT_EQ(one.result->extrinsic.translation, two.result->extrinsic.translation);
  ASSERT_TRUE(one.quality && two.quality);
  EXPECT_EQ(one.quality->uncertainty->translation_cm, two.quality->uncertainty->translation_cm);
  // Nothing was asked to be written: nothing was.
  EXPECT_FALSE(one.result_file_written);
  EXPECT_TRUE(one.result_file_error.empty());
  EXPECT_TRUE(one.report_files.empty());
}

TEST(CalibrationJob, FailuresComeBackInTheOutcome) {
  const std::string dir = test_support::tempDir("tlc_job_");
  // Too few pairs for Algorithm 2: the fit's reason, no result, no file.
  CalibrationJobRequest few = quickRequest(dir);
  few.pairs.resize(3);
  few.parameters.calibration.algorithm = Algorithm::kOutlierRejection;
  const CalibrationJobOutcome failed = runCalibrationJob(few);
  EXPECT_FALSE(failed.result);
  EXPECT_NE(failed.error.find("min_sample"), std::string::npos) << failed.error;
  EXPECT_FALSE(std::filesystem::exists(few.output_file));
  // An unwritable result file: the result stands, the outcome says why the file is missing.
  CalibrationJobRequest unwritable = quickRequest(dir);
  unwritable.output_file = dir + "/no_such_folder/result.yaml";
  unwritable.report_dir.clear();
  const CalibrationJobOutcome kept = runCalibrationJob(unwritable);
  ASSERT_TRUE(kept.result);
  EXPECT_FALSE(kept.result_file_written);
  EXPECT_NE(kept.result_file_error.find("no_such_folder"), std::string::npos) << kept.result_file_error;
}

TEST(CalibrationJob, AStopWritesNothingUnlessTheBestSoFarIsWanted) {
  const std::string dir = test_support::tempDir("tlc_job_");
  const auto stop_in_fit = [](const JobProgress& p) { return !(p.stage == JobProgress::Stage::kFit && p.fit.generation >= 3); };
  CalibrationJobRequest node_like = quickRequest(dir);
  const CalibrationJobOutcome dropped = runCalibrationJob(node_like, stop_in_fit);
  ASSERT_TRUE(dropped.result);
  EXPECT_TRUE(dropped.result->stopped);
  EXPECT_FALSE(dropped.quality) << "no bootstrap after a stopped fit";
  EXPECT_FALSE(std::filesystem::exists(node_like.output_file));
  EXPECT_FALSE(std::filesystem::exists(node_like.report_dir));

  CalibrationJobRequest tool_like = quickRequest(dir);
  tool_like.write_stopped_result = true;
  const CalibrationJobOutcome kept = runCalibrationJob(tool_like, stop_in_fit);
  ASSERT_TRUE(kept.result);
  EXPECT_TRUE(kept.result->stopped);
  EXPECT_TRUE(kept.result_file_written) << kept.result_file_error;

  // A stop that arrives after the fit (a ~reset during the bootstrap) still keeps the disk clean.
  const std::string dir2 = test_support::tempDir("tlc_job_");
  CalibrationJobRequest late = quickRequest(dir2);
  const CalibrationJobOutcome late_out = runCalibrationJob(
      late, [](const JobProgress& p) { return p.stage == JobProgress::Stage::kFit; });
  ASSERT_TRUE(late_out.result);
  EXPECT_FALSE(late_out.result->stopped);
  EXPECT_FALSE(std::filesystem::exists(late.output_file));
}

// Issue 23: the job pairs the candidate frames by association after the first fit, and the
// result (and the pairs it indexes) say which rule made each pair; a front end that kept no
// candidates (the live node today) is told so rather than shown an association that found none.
TEST(CalibrationJob, PairsTheCandidatesByAssociationAndSaysWhichRuleMadeEachPair) {
  const std::string dir = test_support::tempDir("tlc_job_association_");
  CalibrationJobRequest request = quickRequest(dir);
  request.report_dir.clear();
  request.parameters.quality.uncertainty_enabled = false;
  test_support::SyntheticPairsOptions o;
  o.pairs = 12;
  o.seed = 12;
  for (std::size_t i = 0; i < request.pairs.size(); ++i) request.pairs[i].candidate_index = 10 * i;
  std::vector<CalibrationPair> candidates = test_support::makeSyntheticPairs(request.camera, fieldsafeTruth(), o);
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    candidates[i].regions = personRegions(candidates[i].mask);
    candidates[i].mask = cv::Mat();
    candidates[i].rule = PairRule::kAssociation;
    candidates[i].candidate_index = 10 * i + 5;
    candidates[i].stamp_s = 100.5 + static_cast<double>(i);
  }
  request.candidates = candidates;
  request.candidates_collected = true;
  const CalibrationJobOutcome out = runCalibrationJob(request);
  ASSERT_TRUE(out.result) << out.error;
  EXPECT_EQ(out.pairing.mode, PairingMode::kAssociation);
  EXPECT_EQ(out.pairing.counts, 24u);
  EXPECT_GE(out.pairing.association, 8u);
  EXPECT_EQ(out.pairs, out.fitted_pairs.size());
  EXPECT_EQ(out.result->pairs_collected, out.fitted_pairs.size());
  ASSERT_EQ(out.context.pair_rules.size(), out.fitted_pairs.size());
  const YAML::Node y = YAML::LoadFile(request.output_file);
  EXPECT_EQ(y["pairs_by_rule"]["association"].as<std::size_t>(), out.pairing.association);
  EXPECT_LT(rotationErrorRad(out.result->extrinsic, fieldsafeTruth()), 0.2 * kDeg);

  request.candidates_collected = false;
  request.candidates.clear();
  const CalibrationJobOutcome node = runCalibrationJob(request);
  ASSERT_TRUE(node.result) << node.error;
  EXPECT_EQ(node.pairing.mode, PairingMode::kCounts);
  EXPECT_EQ(node.pairing.association, 0u);
  EXPECT_NE(node.pairing.note.find("pairing association not applied"), std::string::npos) << node.pairing.note;
}
