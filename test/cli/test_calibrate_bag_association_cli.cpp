// calibrate_bag and pairing by association (issue 23), on a drive with realistic noise (missed
// people, false clusters and mask blobs: many frames with unequal counts): the default run adds
// association pairs and says how many each rule made (result keys, summary line, each pair's
// rule); pairing counts and refine none are the count rule alone; a wrong initial extrinsic
// (5 deg, 30 cm off) is refused with a note and the result still lands at the truth; the final
// round (issue 24) pairs the skipped frames and says so, and is off when asked; the new keys' bad
// values are one line each.

#include "cli_run.hpp"
#include "../support/test_files.hpp"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <Eigen/Geometry>

#include <cmath>
#include <fstream>
#include <string>


namespace {

using tlc_cli_test::RunResult;

class CalibrateBagAssociationCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = thermal_lidar_calibration::test_support::tempDir("tlc_cli_association_");
    const RunResult gen = tlc_cli_test::runTool(
        MAKE_SYNTHETIC_BAG_EXE,
        "--seed 2 --frames 600 --noise realistic --output '" + dir_ + "/drive.bag' --truth '" + dir_ +
            "/truth.yaml'",
        dir_);
    ASSERT_EQ(gen.exit_code, 0) << gen.err;
  }
  // Without the bootstrap: it is not what these tests are about, and would double their time.
  static RunResult calibrate(const std::string& out, const std::string& config_lines, const std::string& extra = "") {
    std::ofstream(dir_ + "/" + out + ".config.yaml") << "uncertainty: false\n" << config_lines;
    return tlc_cli_test::runTool(CALIBRATE_BAG_EXE,
                                 "--bag '" + dir_ + "/drive.bag' --truth '" + dir_ + "/truth.yaml' --config '" +
                                     dir_ + "/" + out + ".config.yaml' --output '" + dir_ + "/" + out + ".yaml' " +
                                     extra,
                                 dir_);
  }
  static std::string dir_;
};
std::string CalibrateBagAssociationCli::dir_;

TEST_F(CalibrateBagAssociationCli, TheDefaultRunAddsAssociationPairsAndSaysHowManyEachRuleMade) {
  const RunResult r = calibrate("default", "");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const YAML::Node y = YAML::LoadFile(dir_ + "/default.yaml");
  const int counts = y["pairs_by_rule"]["counts"].as<int>();
  const int association = y["pairs_by_rule"]["association"].as<int>();
  EXPECT_GT(counts, 20);
  EXPECT_GE(association, 10);  // frames with a missed person, a false cluster or a false blob
  EXPECT_EQ(counts + association, y["pairs_collected"].as<int>());
  EXPECT_EQ(y["association"]["pairing"].as<std::string>(), "association");
  EXPECT_GE(y["association"]["rounds"].as<int>(), 1);
  EXPECT_FALSE(y["association"]["initial_extrinsic_used"].as<bool>());
  int rule_association = 0;
  for (const YAML::Node& pair : y["pairs"]) rule_association += pair["rule"].as<std::string>() == "association";
  EXPECT_EQ(rule_association, association);
  EXPECT_LT(y["truth"]["rotation_error_deg"].as<double>(), 0.2);
  EXPECT_LT(y["truth"]["translation_error_m"].as<double>(), 0.03);
  EXPECT_NE(r.out.find("  pairs by rule    counts " + std::to_string(counts) + ", association " +
                       std::to_string(association) + " (of "),
            std::string::npos)
      << r.out;
  // The final round: the skipped frames held, the pairs it added among the association's.
  const int skipped = y["association"]["skipped_frames"].as<int>();
  const int added = y["association"]["final_round_pairs"].as<int>();
  EXPECT_TRUE(y["association"]["final_round"].as<bool>());
  EXPECT_GT(skipped, 50);  // skip_frames 3 after each of the count rule's pairs
  EXPECT_GT(added, 50);
  EXPECT_LE(added, association);
  EXPECT_NE(r.out.find(" skipped frames: +" + std::to_string(added) + ")"), std::string::npos) << r.out;
}

TEST_F(CalibrateBagAssociationCli, WithoutTheFinalRoundTheSkippedFramesStaySkipped) {
  const RunResult r = calibrate("no_final", "association_final_round: false\n");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const YAML::Node y = YAML::LoadFile(dir_ + "/no_final.yaml");
  EXPECT_FALSE(y["association"]["final_round"].as<bool>());
  EXPECT_EQ(y["association"]["skipped_frames"].as<int>(), 0);
  EXPECT_EQ(y["association"]["final_round_pairs"].as<int>(), 0);
  EXPECT_GE(y["pairs_by_rule"]["association"].as<int>(), 10);
  EXPECT_EQ(r.out.find("final round"), std::string::npos) << r.out;
}

TEST_F(CalibrateBagAssociationCli, PairingCountsAndThePaperModeAreTheCountRuleAlone) {
  for (const std::string& config : {std::string("pairing: counts\n"), std::string("refine: none\n")}) {
    const RunResult r = calibrate("counts", config);
    ASSERT_EQ(r.exit_code, 0) << config << r.err;
    const YAML::Node y = YAML::LoadFile(dir_ + "/counts.yaml");
    EXPECT_EQ(y["pairs_by_rule"]["association"].as<int>(), 0) << config;
    EXPECT_EQ(y["pairs_by_rule"]["counts"].as<int>(), y["pairs_collected"].as<int>()) << config;
    EXPECT_EQ(y["association"]["pairing"].as<std::string>(), "counts") << config;
    EXPECT_EQ(y["association"]["rounds"].as<int>(), 0) << config;
    EXPECT_NE(r.out.find("(pairing counts)"), std::string::npos) << r.out;
  }
}

TEST_F(CalibrateBagAssociationCli, AWrongInitialExtrinsicIsRefusedAndTheResultStillFindsTheTruth) {
  const YAML::Node truth = YAML::LoadFile(dir_ + "/truth.yaml");
  const Eigen::Vector3d r(truth["rotation_vector"][0].as<double>(), truth["rotation_vector"][1].as<double>(),
                          truth["rotation_vector"][2].as<double>());
  const Eigen::Matrix3d turned =
      Eigen::AngleAxisd(5.0 * M_PI / 180.0, Eigen::Vector3d::UnitY()).toRotationMatrix() *
      Eigen::AngleAxisd(r.norm(), r.normalized()).toRotationMatrix();
  const Eigen::AngleAxisd wrong(turned);
  const Eigen::Vector3d rv = wrong.angle() * wrong.axis();
  const std::string start = dir_ + "/start.yaml";
  std::ofstream(start) << "rotation_vector: [" << rv.x() << ", " << rv.y() << ", " << rv.z() << "]\ntranslation: ["
                       << truth["translation"][0].as<double>() + 0.3 << ", " << truth["translation"][1].as<double>()
                       << ", " << truth["translation"][2].as<double>() << "]\n";
  const RunResult run = calibrate("wrong_start", "initial_extrinsic_file: '" + start + "'\n");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const YAML::Node y = YAML::LoadFile(dir_ + "/wrong_start.yaml");
  EXPECT_FALSE(y["association"]["initial_extrinsic_used"].as<bool>());
  EXPECT_NE(y["association"]["note"].as<std::string>().find("refused"), std::string::npos);
  EXPECT_NE(run.out.find("  association      initial extrinsic " + start + " refused"), std::string::npos) << run.out;
  EXPECT_LT(y["truth"]["rotation_error_deg"].as<double>(), 0.2);
  EXPECT_LT(y["truth"]["translation_error_m"].as<double>(), 0.03);
}

TEST_F(CalibrateBagAssociationCli, BadAssociationValuesAreOneLineEach) {
  const struct {
    const char* line;
    const char* key;
  } cases[] = {{"pairing: both\n", "pairing"},
               {"association_margin: 2\n", "association_margin"},
               {"association_min_overlap: -0.1\n", "association_min_overlap"},
               {"association_max_rounds: 0\n", "association_max_rounds"},
               {"association_final_round: sometimes\n", "association_final_round"},
               {"initial_extrinsic_min_agreement: 1.5\n", "initial_extrinsic_min_agreement"},
               {"initial_extrinsic_file: /nonexistent/start.yaml\n", "initial_extrinsic_file"}};
  for (const auto& c : cases) {
    const RunResult r = calibrate("bad", c.line, "--quiet");
    const std::string e = tlc_cli_test::expectOneLineError(r, "calibrate_bag: error: ");
    EXPECT_NE(e.find(c.key), std::string::npos) << c.line << e;
  }
}

}  // namespace
