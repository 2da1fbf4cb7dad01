// calibrate_bag's answer to "can I trust it?" (issue 8): the result file's uncertainty,
// coverage, verdict and reference keys, the verdict on a drive with an empty image region,
// --reference against the truth, and the visual report (--report).

#include "cli_run.hpp"
#include "../support/test_files.hpp"

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <yaml-cpp/yaml.h>

#include <fstream>
#include <iterator>
#include <string>


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
  // Calibrates `name`.bag into `output`.yaml (`name`.yaml when empty).
  static RunResult calibrate(const std::string& name, const std::string& extra = "",
                             const std::string& output = "") {
    return tlc_cli_test::runTool(CALIBRATE_BAG_EXE,
                                 "--bag '" + dir_ + "/" + name + ".bag' --output '" + dir_ + "/" +
                                     (output.empty() ? name : output) + ".yaml' " + extra,
                                 dir_);
  }
  // The default run on the full drive with --reference (the truth) and --report, into
  // full_run.yaml: made once, read by the tests of each (a default run is this suite's longest
  // step), and written where the other tests' runs on the same bag do not write.
  static const RunResult& fullRun() {
    static const RunResult r = calibrate(
        "full", "--reference '" + dir_ + "/full.truth.yaml' --report '" + dir_ + "/report'", "full_run");
    return r;
  }
  static std::string dir_;
};
std::string CalibrateBagQualityCli::dir_;

// Every key of docs/INTERFACE.md "Quality", and --reference with the truth: the difference lies
// within the stated intervals on every axis, and the truth's loss is reported beside ours.
TEST_F(CalibrateBagQualityCli, ResultHoldsUncertaintyCoverageVerdictAndTheReference) {
  const std::string truth = dir_ + "/full.truth.yaml";
  const RunResult& r = fullRun();
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("  uncertainty      95 % intervals"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("  verdict          "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("within the intervals on every axis"), std::string::npos) << r.out;
  const YAML::Node y = YAML::LoadFile(dir_ + "/full_run.yaml");
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

// --report DIR: the pictures exist with their stated sizes, are not blank, and index.html shows
// them with the numbers.
TEST_F(CalibrateBagQualityCli, ReportWritesThePicturesAndAnIndex) {
  const std::string report = dir_ + "/report";
  const RunResult& r = fullRun();
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("report: " + report + "/index.html (6 files)"), std::string::npos) << r.out;
  const struct {
    const char* file;
    int width, height;
  } pictures[] = {{"overlays.png", 960, 512},    {"coverage.png", 640, 512},
                  {"convergence.png", 900, 420}, {"pair_losses.png", 900, 360},
                  {"uncertainty.png", 900, 360}};
  std::ifstream index_file(report + "/index.html");
  const std::string index((std::istreambuf_iterator<char>(index_file)), std::istreambuf_iterator<char>());
  for (const auto& p : pictures) {
    const cv::Mat image = cv::imread(report + "/" + p.file);
    ASSERT_FALSE(image.empty()) << p.file;
    EXPECT_EQ(image.cols, p.width) << p.file;
    EXPECT_EQ(image.rows, p.height) << p.file;
    cv::Scalar mean, stddev;
    cv::meanStdDev(image, mean, stddev);
    EXPECT_GT(stddev[0] + stddev[1] + stddev[2], 10.0) << p.file << " is blank";
    EXPECT_NE(index.find(std::string("<img src=\"") + p.file + "\">"), std::string::npos) << p.file;
  }
  const YAML::Node y = YAML::LoadFile(dir_ + "/full_run.yaml");
  EXPECT_NE(index.find(y["verdict"].as<std::string>()), std::string::npos) << index;
  EXPECT_NE(index.find("loss (Eq. 3, nearest pixel)"), std::string::npos);
  EXPECT_NE(index.find("refine_ring_end_weight"), std::string::npos) << "which loss each stage reads";
  // The overlays show the result: on a clean drive the best pairs' points lie on the masks,
  // so the top row has green (BGR ~ (60, 170, 60)) and no red points.
  const cv::Mat overlays = cv::imread(report + "/overlays.png");
  const cv::Mat top = overlays(cv::Rect(0, 0, overlays.cols, overlays.rows / 2));
  cv::Mat green, red;
  cv::inRange(top, cv::Scalar(50, 160, 50), cv::Scalar(70, 180, 70), green);
  cv::inRange(top, cv::Scalar(30, 30, 210), cv::Scalar(50, 50, 230), red);
  EXPECT_GT(cv::countNonZero(green), 20);
  EXPECT_EQ(cv::countNonZero(red), 0);
  // The report belongs to a calibration: with --monitor it is a usage error.
  const RunResult usage = calibrate("full", "--monitor --reference x.yaml --report '" + report + "'");
  EXPECT_EQ(usage.exit_code, 2) << usage.err;
}

// A --report directory that cannot be made is one line at once, before the bag is read.
TEST_F(CalibrateBagQualityCli, UnusableReportDirectoryIsOneLineBeforeAnyWork) {
  const RunResult r = calibrate("full", "--report /proc/no_such_report --quiet");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("calibrate_bag: error: --report /proc/no_such_report: "), std::string::npos) << r.err;
  EXPECT_EQ(r.out.find("read:"), std::string::npos) << "the bag was read first:\n" << r.out;
}
