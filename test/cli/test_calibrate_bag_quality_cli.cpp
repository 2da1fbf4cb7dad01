// calibrate_bag's answer to "can I trust it?" (issue 8): the result file's uncertainty,
// coverage, verdict and reference keys, the verdict on a drive with an empty image region, and
// --reference against the truth.

#include "cli_run.hpp"
#include "../support/test_files.hpp"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <fstream>
#include <string>

#ifndef CALIBRATE_BAG_EXE
#error "CALIBRATE_BAG_EXE must be defined to the calibrate_bag binary"
#endif
#ifndef MAKE_SYNTHETIC_BAG_EXE
#error "MAKE_SYNTHETIC_BAG_EXE must be defined to the make_synthetic_bag binary"
#endif

namespace {

using tlc_cli_test::RunResult;

class CalibrateBagQualityCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = thermal_lidar_calibration::test_support::tempDir("tlc_cli_quality_");
    for (const char* name : {"full", "left_empty"}) {
      const std::string extra = std::string(name) == "left_empty" ? " --empty-image-region left" : "";
      const RunResult gen = tlc_cli_test::runTool(
          MAKE_SYNTHETIC_BAG_EXE,
          "--seed 1 --output '" + dir_ + "/" + name + ".bag' --truth '" + dir_ + "/" + name + ".truth.yaml'" + extra,
          dir_);
      ASSERT_EQ(gen.exit_code, 0) << gen.err;
    }
  }
  static RunResult calibrate(const std::string& name, const std::string& extra = "") {
    return tlc_cli_test::runTool(CALIBRATE_BAG_EXE,
                                 "--bag '" + dir_ + "/" + name + ".bag' --output '" + dir_ + "/" + name +
                                     ".yaml' " + extra,
                                 dir_);
  }
  static std::string dir_;
};
std::string CalibrateBagQualityCli::dir_;

// Every key of docs/INTERFACE.md "Quality", and --reference with the truth: the difference lies
// within the stated intervals on every axis, and the truth's loss is reported beside ours.
TEST_F(CalibrateBagQualityCli, ResultHoldsUncertaintyCoverageVerdictAndTheReference) {
  const std::string truth = dir_ + "/full.truth.yaml";
  const RunResult r = calibrate("full", "--reference '" + truth + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("  uncertainty      95 % intervals"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("  verdict          "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("within the intervals on every axis"), std::string::npos) << r.out;
  const YAML::Node y = YAML::LoadFile(dir_ + "/full.yaml");
  ASSERT_TRUE(y["uncertainty"]);
  EXPECT_EQ(y["uncertainty"]["method"].as<std::string>(), "bootstrap");
  EXPECT_GE(y["uncertainty"]["resamples"].as<int>(), 50);
  for (const char* key : {"rotation_deg", "translation_cm"}) {
    ASSERT_EQ(y["uncertainty"][key].size(), 3u) << key;
    for (int i = 0; i < 3; ++i) EXPECT_GT(y["uncertainty"][key][i].as<double>(), 0.0) << key;
  }
  ASSERT_TRUE(y["coverage"]);
  EXPECT_EQ(y["coverage"]["grid_person_pixels"].size(), 16u);
  EXPECT_GT(y["coverage"]["distinct_positions"].as<int>(), 0);
  const std::string verdict = y["verdict"].as<std::string>();
  EXPECT_TRUE(verdict == "good" || verdict == "usable" || verdict == "collect_more") << verdict;
  EXPECT_GE(y["verdict_reasons"].size(), 1u);
  ASSERT_TRUE(y["reference"]);
  EXPECT_EQ(y["reference"]["source"].as<std::string>(), "file");
  EXPECT_EQ(y["reference"]["origin"].as<std::string>(), truth);
  EXPECT_EQ(y["reference"]["translation_difference_cm"].size(), 3u);
  EXPECT_GT(y["reference"]["loss"].as<double>(), 0.0);
  for (int i = 0; i < 3; ++i) {
    EXPECT_LE(std::abs(y["reference"]["rotation_difference_axes_deg"][i].as<double>()),
              y["uncertainty"]["rotation_deg"][i].as<double>())
        << "rotation axis " << i;
    EXPECT_LE(std::abs(y["reference"]["translation_difference_cm"][i].as<double>()),
              y["uncertainty"]["translation_cm"][i].as<double>())
        << "translation axis " << i;
  }
}

// The paper's Table 5 case: nobody ever in the left third of the image. The verdict says to
// collect more and names the region.
TEST_F(CalibrateBagQualityCli, EmptyLeftThirdGivesCollectMoreNamingIt) {
  const RunResult r = calibrate("left_empty", "--quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const YAML::Node y = YAML::LoadFile(dir_ + "/left_empty.yaml");
  EXPECT_EQ(y["verdict"].as<std::string>(), "collect_more");
  bool named = false;
  for (const auto& reason : y["verdict_reasons"]) {
    named = named || reason.as<std::string>().find("left third") != std::string::npos;
  }
  EXPECT_TRUE(named) << YAML::Dump(y["verdict_reasons"]);
  EXPECT_LT(y["coverage"]["third_fractions"][0].as<double>(), 0.01);
}

TEST_F(CalibrateBagQualityCli, UnreadableReferenceIsOneLine) {
  std::ofstream(dir_ + "/bad_reference.yaml") << "translation: [1, 2]\n";
  const RunResult r = calibrate("full", "--quiet --reference '" + dir_ + "/bad_reference.yaml'");
  const std::string e = tlc_cli_test::expectOneLineError(r, "calibrate_bag: error: ");
  EXPECT_NE(e.find("--reference"), std::string::npos) << e;
  EXPECT_NE(e.find("translation"), std::string::npos) << e;
}

}  // namespace
