// Result file: every INTERFACE key, the extras, and reading it (or a truth file) back.

#include "thermal_lidar_calibration/app/files/result_file.hpp"

#include "../support/test_files.hpp"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <fstream>
#include <iomanip>
#include <stdexcept>

namespace tlc = thermal_lidar_calibration;
using namespace tlc;

namespace {

std::string tempDir() { return tlc::test_support::tempDir("tlc_result_"); }

tlc::CalibrationResult sampleResult() {
  tlc::CalibrationResult r;
  r.extrinsic.rotation_vector = Eigen::Vector3d(1.2, -1.1, 1.3);
  r.extrinsic.translation = Eigen::Vector3d(0.05, -0.31, 0.12);
  r.loss = 0.83;
  r.loss_bilinear = 0.79;
  r.evolution_extrinsic.rotation_vector = Eigen::Vector3d(1.21, -1.09, 1.29);
  r.evolution_extrinsic.translation = Eigen::Vector3d(0.06, -0.3, 0.1);
  r.evolution_loss = 0.91;
  r.evolution_full_length = true;
  r.pair_losses = {0.5, 4.0, 0.7};
  r.inliers = {true, false, true};
  r.pairs_used = 2;
  r.pairs_collected = 3;
  r.evaluations = 12345;
  r.seconds = 3.25;
  return r;
}

}  // namespace

TEST(ResultFile, PairStampsSinceTheEpochKeepTheirMicroseconds) {
  const std::string path = tempDir() + "/stamps.yaml";
  ResultContext ctx;
  ctx.pair_stamps_s = {1600000054.2993, 1600000054.35071, 1600000054.4};
  writeResultFile(path, sampleResult(), ctx);
  const YAML::Node y = YAML::LoadFile(path);
  ASSERT_EQ(y["pairs"].size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(y["pairs"][i]["stamp"].as<double>(), ctx.pair_stamps_s[i], 1e-6) << i;
  }
  EXPECT_DOUBLE_EQ(y["loss"].as<double>(), 0.83) << "the other values keep the file's precision";
}

TEST(ResultFile, HasEveryInterfaceKeyAndRoundTrips) {
  const std::string path = tempDir() + "/result.yaml";
  ResultContext ctx;
  ctx.lidar_frame = "velodyne";
  ctx.camera_frame = "thermal_optical";
  ctx.source = "in.bag";
  ctx.pair_stamps_s = {10.0, 11.5, 12.25};
  ctx.parameters.calibration.seed = 7;
  const tlc::CalibrationResult r = sampleResult();
  writeResultFile(path, r, ctx);

  const YAML::Node y = YAML::LoadFile(path);
  EXPECT_FALSE(y["truth"]) << "a truth block without --truth";
  for (const char* key : {"lidar_frame", "camera_frame", "rotation_vector", "translation",
                          "rotation_matrix", "quaternion_xyzw", "loss", "pairs_used",
                          "pairs_collected", "loss_bilinear", "evolution", "pairs", "parameters",
                          "algorithm", "refine", "seed", "run_time_s", "evaluations", "source",
                          "created"}) {
    EXPECT_TRUE(y[key]) << key;
  }
  EXPECT_EQ(y["lidar_frame"].as<std::string>(), "velodyne");
  EXPECT_EQ(y["camera_frame"].as<std::string>(), "thermal_optical");
  EXPECT_DOUBLE_EQ(y["loss"].as<double>(), 0.83);
  EXPECT_EQ(y["pairs_used"].as<int>(), 2);
  EXPECT_EQ(y["pairs_collected"].as<int>(), 3);
  EXPECT_EQ(y["rotation_matrix"].size(), 9u);
  EXPECT_EQ(y["quaternion_xyzw"].size(), 4u);
  EXPECT_EQ(y["seed"].as<int>(), 7);
  EXPECT_EQ(y["algorithm"].as<int>(), 2);
  EXPECT_EQ(y["refine"].as<std::string>(), "local");
  ASSERT_EQ(y["pairs"].size(), 3u);
  EXPECT_DOUBLE_EQ(y["pairs"][1]["stamp"].as<double>(), 11.5);
  EXPECT_DOUBLE_EQ(y["pairs"][1]["loss"].as<double>(), 4.0);
  EXPECT_FALSE(y["pairs"][1]["inlier"].as<bool>());
  EXPECT_EQ(y["parameters"]["population_size"].as<int>(), 500);
  EXPECT_DOUBLE_EQ(y["evolution"]["loss"].as<double>(), 0.91);
  EXPECT_TRUE(y["evolution"]["full_length"].as<bool>());

  // The quaternion and matrix agree with the rotation vector.
  const Eigen::Matrix3d R = r.extrinsic.rotationMatrix();
  for (int i = 0; i < 9; ++i) {
    EXPECT_NEAR(y["rotation_matrix"][i].as<double>(), R(i / 3, i % 3), 1e-9);
  }
  const Eigen::Quaterniond q(y["quaternion_xyzw"][3].as<double>(),
                             y["quaternion_xyzw"][0].as<double>(),
                             y["quaternion_xyzw"][1].as<double>(),
                             y["quaternion_xyzw"][2].as<double>());
  EXPECT_LT((q.toRotationMatrix() - R).norm(), 1e-9);

  const tlc::Extrinsic back = readExtrinsicFile(path);
  EXPECT_LT((back.rotation_vector - r.extrinsic.rotation_vector).norm(), 1e-9);
  EXPECT_LT((back.translation - r.extrinsic.translation).norm(), 1e-12);
}

TEST(ResultFile, SaysWhetherTheVerticalCentringMovedTheEstimate) {
  const std::string dir = tempDir();
  tlc::CalibrationResult r = sampleResult();
  writeResultFile(dir + "/paper.yaml", r, ResultContext{});
  EXPECT_FALSE(YAML::LoadFile(dir + "/paper.yaml")["vertical_centring"]) << "not run: no key";

  r.vertical_centring.ran = true;
  r.vertical_centring.applied = true;
  r.vertical_centring.skipped_because = "";
  r.vertical_centring.shift_rotation_px = 1.25;
  r.vertical_centring.shift_translation_px = -0.5;
  r.vertical_centring.shift_roll_px = 0.75;
  r.vertical_centring.fitting = {0, 2};
  writeResultFile(dir + "/applied.yaml", r, ResultContext{});
  const YAML::Node applied = YAML::LoadFile(dir + "/applied.yaml")["vertical_centring"];
  ASSERT_TRUE(applied);
  EXPECT_TRUE(applied["applied"].as<bool>());
  EXPECT_FALSE(applied["skipped_because"]);
  EXPECT_DOUBLE_EQ(applied["moved_px"][0].as<double>(), 1.25);
  EXPECT_DOUBLE_EQ(applied["moved_px"][1].as<double>(), -0.5);
  EXPECT_DOUBLE_EQ(applied["moved_px"][2].as<double>(), 0.75);
  EXPECT_EQ(applied["fitting_pairs"].as<int>(), 2);

  r.vertical_centring.applied = false;
  r.vertical_centring.skipped_because = "too few pairs fit within the margin";
  r.vertical_centring.shift_rotation_px = r.vertical_centring.shift_translation_px = 0.0;
  r.vertical_centring.shift_roll_px = 0.0;
  writeResultFile(dir + "/skipped.yaml", r, ResultContext{});
  const YAML::Node skipped = YAML::LoadFile(dir + "/skipped.yaml")["vertical_centring"];
  EXPECT_FALSE(skipped["applied"].as<bool>());
  EXPECT_EQ(skipped["skipped_because"].as<std::string>(), "too few pairs fit within the margin");
}

TEST(ResultFile, ReadsRotationMatrixOnlyFiles) {
  const std::string path = tempDir() + "/truth.yaml";
  tlc::Extrinsic e;
  e.rotation_vector = Eigen::Vector3d(0.3, -0.2, 0.1);
  e.translation = Eigen::Vector3d(1, 2, 3);
  const Eigen::Matrix3d R = e.rotationMatrix();
  std::ofstream out(path);
  out << "translation: [1, 2, 3]\nrotation_matrix: [";
  for (int i = 0; i < 9; ++i) out << (i ? ", " : "") << std::setprecision(17) << R(i / 3, i % 3);
  out << "]\n";
  out.close();
  const tlc::Extrinsic back = readExtrinsicFile(path);
  EXPECT_LT((back.rotation_vector - e.rotation_vector).norm(), 1e-9);
}

TEST(ResultFile, BadExtrinsicFilesAreErrors) {
  const std::string dir = tempDir();
  EXPECT_THROW(readExtrinsicFile(dir + "/missing.yaml"), std::invalid_argument);
  std::ofstream(dir + "/no_t.yaml") << "rotation_vector: [0, 0, 0]\n";
  EXPECT_THROW(readExtrinsicFile(dir + "/no_t.yaml"), std::invalid_argument);
  std::ofstream(dir + "/no_r.yaml") << "translation: [0, 0, 0]\n";
  EXPECT_THROW(readExtrinsicFile(dir + "/no_r.yaml"), std::invalid_argument);
  std::ofstream(dir + "/bad_r.yaml") << "translation: [0, 0, 0]\nrotation_matrix: [2, 0, 0, 0, 1, "
                                        "0, 0, 0, 1]\n";
  EXPECT_THROW(readExtrinsicFile(dir + "/bad_r.yaml"), std::invalid_argument);
}

TEST(ResultFile, UnwritablePathIsARuntimeError) {
  EXPECT_THROW(writeResultFile("/nonexistent_dir/result.yaml", sampleResult(), ResultContext{}),
               std::runtime_error);
}

// Issue 23: how many pairs each rule made, the association block and each pair's rule.
TEST(ResultFile, SaysWhichRuleMadeEachPair) {
  const std::string path = tempDir() + "/pairing.yaml";
  ResultContext ctx;
  ctx.pair_stamps_s = {10.0, 11.5, 12.25};
  ctx.pair_rules = {PairRule::kCounts, PairRule::kAssociation, PairRule::kCounts};
  PairingSummary pairing;
  pairing.mode = PairingMode::kAssociation;
  pairing.counts = 2;
  pairing.association = 1;
  pairing.candidates = 9;
  pairing.rounds = 2;
  pairing.note = "initial extrinsic x.yaml refused: ...";
  ctx.pairing = pairing;
  writeResultFile(path, sampleResult(), ctx);
  const YAML::Node y = YAML::LoadFile(path);
  EXPECT_EQ(y["pairs_by_rule"]["counts"].as<int>(), 2);
  EXPECT_EQ(y["pairs_by_rule"]["association"].as<int>(), 1);
  EXPECT_EQ(y["association"]["pairing"].as<std::string>(), "association");
  EXPECT_EQ(y["association"]["candidate_frames"].as<int>(), 9);
  EXPECT_EQ(y["association"]["rounds"].as<int>(), 2);
  EXPECT_TRUE(y["association"]["converged"].as<bool>());
  EXPECT_FALSE(y["association"]["initial_extrinsic_used"].as<bool>());
  EXPECT_EQ(y["association"]["note"].as<std::string>(), pairing.note);
  EXPECT_EQ(y["pairs"][1]["rule"].as<std::string>(), "association");
  EXPECT_EQ(y["pairs"][2]["rule"].as<std::string>(), "counts");

  ResultContext plain;  // without a pairing summary (older callers): no such keys
  writeResultFile(path, sampleResult(), plain);
  EXPECT_FALSE(YAML::LoadFile(path)["pairs_by_rule"]);
  EXPECT_FALSE(YAML::LoadFile(path)["pairs"][0]["rule"]);
}
