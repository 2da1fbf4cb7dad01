// calibrate_bag and the camera's time offset (issue 21), on a field drive (stops, turns, half the
// people walking) whose images show the world 60 ms after their stamps: the default run
// estimates the offset with the extrinsic (result keys, summary line, the one-line warning, the
// report's profile); time_offset_mode none lands decimetres off and its verdict names timing, not
// the amount of data; fixed applies the given offset; the keys' bad values are one line each.

#include "cli_run.hpp"
#include "../support/test_files.hpp"

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <string>


namespace {

using tlc_cli_test::RunResult;

class CalibrateBagTimingCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = thermal_lidar_calibration::test_support::tempDir("tlc_cli_timing_");
    // 1200 frames (76 pairs): the drive resolves the offset to 4.3 ms, under the 5 ms gate.
    const RunResult gen = tlc_cli_test::runTool(
        MAKE_SYNTHETIC_BAG_EXE,
        "--seed 1 --speed-profile field --walking-fraction 0.5 --camera-time-offset 0.06 --output '" + dir_ +
            "/late.bag' --truth '" + dir_ + "/late.truth.yaml'",
        dir_);
    ASSERT_EQ(gen.exit_code, 0) << gen.err;
  }
  // Without the bootstrap: it is not what these tests are about, and would double their time.
  static RunResult calibrate(const std::string& out, const std::string& config_lines, const std::string& extra = "") {
    std::ofstream(dir_ + "/" + out + ".config.yaml") << "uncertainty: false\n" << config_lines;
    return tlc_cli_test::runTool(CALIBRATE_BAG_EXE,
                                 "--bag '" + dir_ + "/late.bag' --truth '" + dir_ + "/late.truth.yaml' --config '" +
                                     dir_ + "/" + out + ".config.yaml' --output '" + dir_ + "/" + out + ".yaml' " +
                                     extra,
                                 dir_);
  }
  static YAML::Node truthOf(const YAML::Node& result) { return result["truth"]; }
  static std::string dir_;
};
std::string CalibrateBagTimingCli::dir_;

TEST_F(CalibrateBagTimingCli, TheDefaultRunEstimatesTheOffsetWithTheExtrinsic) {
  const std::string report = dir_ + "/report";
  const RunResult r = calibrate("estimate", "", "--report '" + report + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const YAML::Node y = YAML::LoadFile(dir_ + "/estimate.yaml");
  EXPECT_EQ(y["time_offset_mode"].as<std::string>(), "estimate");
  EXPECT_NEAR(y["time_offset_s"].as<double>(), 0.06, 0.005);
  EXPECT_GT(y["pairs_with_motion"].as<int>(), 60);
  EXPECT_GT(y["loss_without_timing"].as<double>(), 3.0 * y["loss"].as<double>());
  ASSERT_TRUE(y["time_offset_profile"]);
  EXPECT_EQ(y["time_offset_profile"]["offsets_s"].size(), y["time_offset_profile"]["losses_px"].size());
  // Searched over the whole range (+-200 ms) by the first fit, on the count rule's pairs it used.
  EXPECT_GE(y["time_offset_profile"]["offsets_s"].size(), 15u);
  EXPECT_GT(y["time_offset_profile"]["pairs"].as<int>(), 0);
  EXPECT_LE(y["time_offset_profile"]["pairs"].as<int>(), y["pairs_by_rule"]["counts"].as<int>());
  EXPECT_LT(y["timing"]["resolution_ms"].as<double>(), 5.0);
  EXPECT_LT(truthOf(y)["rotation_error_deg"].as<double>(), 0.1);
  EXPECT_LT(truthOf(y)["translation_error_m"].as<double>(), 0.03);
  // The summary line and one warning line naming the offset and what to set.
  const auto line = r.out.find("  time offset      +");
  ASSERT_NE(line, std::string::npos) << r.out;
  EXPECT_NEAR(std::stod(r.out.substr(line + 19)), 60.0, 5.0) << r.out;  // ms
  EXPECT_NE(r.out.find("(estimated"), std::string::npos) << r.out;
  const std::string said = "calibrate_bag: warning: the thermal images were captured ";
  const auto warning = r.err.find(said);
  ASSERT_NE(warning, std::string::npos) << r.err;
  EXPECT_NEAR(std::stod(r.err.substr(warning + said.size())), 60.0, 5.0) << r.err;
  EXPECT_NE(r.err.find("time_offset_mode: fixed", warning), std::string::npos) << r.err;
  // The report shows the profile and says the offset.
  EXPECT_FALSE(cv::imread(report + "/time_offset.png").empty());
  std::ifstream index_file(report + "/index.html");
  const std::string index((std::istreambuf_iterator<char>(index_file)), std::istreambuf_iterator<char>());
  EXPECT_NE(index.find("camera time offset"), std::string::npos);
  EXPECT_NE(index.find("<img src=\"time_offset.png\">"), std::string::npos);
}

TEST_F(CalibrateBagTimingCli, IgnoringTheOffsetIsDecimetresOffAndTheVerdictNamesTiming) {
  // The count rule's pairs alone, as when this was measured: association's extra pairs (issue 23)
  // take the offset-blind fit to 6 cm on this drive, which is not what this test is about.
  const RunResult r = calibrate("none", "time_offset_mode: none\npairing: counts\n", "--quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const YAML::Node y = YAML::LoadFile(dir_ + "/none.yaml");
  EXPECT_EQ(y["time_offset_mode"].as<std::string>(), "none");
  EXPECT_EQ(y["time_offset_s"].as<double>(), 0.0);
  EXPECT_GT(truthOf(y)["translation_error_m"].as<double>(), 0.08);
  ASSERT_GE(y["verdict_reasons"].size(), 1u);
  EXPECT_EQ(y["verdict_reasons"][0].as<std::string>().rfind("timing: the residuals follow the people's motion", 0), 0u)
      << YAML::Dump(y["verdict_reasons"]);
}

TEST_F(CalibrateBagTimingCli, FixedAppliesTheGivenOffset) {
  const RunResult r = calibrate("fixed", "time_offset_mode: fixed\ntime_offset_s: 0.06\n", "--quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const YAML::Node y = YAML::LoadFile(dir_ + "/fixed.yaml");
  EXPECT_EQ(y["time_offset_mode"].as<std::string>(), "fixed");
  EXPECT_DOUBLE_EQ(y["time_offset_s"].as<double>(), 0.06);
  EXPECT_FALSE(y["time_offset_profile"]);
  EXPECT_LT(truthOf(y)["translation_error_m"].as<double>(), 0.03);
}

TEST_F(CalibrateBagTimingCli, BadTimingValuesAreOneLineEach) {
  const struct {
    const char* line;
    const char* key;
  } cases[] = {{"time_offset_mode: sometimes\n", "time_offset_mode"},
               {"time_offset_s: 3\n", "time_offset_s"},
               {"time_offset_max_s: 0\n", "time_offset_max_s"},
               {"time_offset_s: 0.3\n", "time_offset_s"},  // beyond time_offset_max_s (0.2)
               {"time_offset_keep_start_sigmas: -1\n", "time_offset_keep_start_sigmas"},
               {"motion_window_scans: 0\n", "motion_window_scans"},
               {"point_time_field: ''\n", "point_time_field"},
               {"monitor_timing_explained_fraction: 2\n", "monitor_timing_explained_fraction"}};
  for (const auto& c : cases) {
    const RunResult r = calibrate("bad", c.line, "--quiet");
    const std::string e = tlc_cli_test::expectOneLineError(r, "calibrate_bag: error: ");
    EXPECT_NE(e.find(c.key), std::string::npos) << c.line << e;
  }
}

}  // namespace
