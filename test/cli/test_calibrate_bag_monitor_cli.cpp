// calibrate_bag --monitor (issue 9): a drive with a mid-drive bump ends in ERROR, confirmed after
// the bump and never before it, with the timeline beside the result; the same drive without the
// bump stays OK throughout; the watch pairs by association unless `pairing: counts` (issue 23).

#include "cli_run.hpp"
#include "../support/test_files.hpp"

#include <gtest/gtest.h>
#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>


namespace {

using tlc_cli_test::RunResult;

class CalibrateBagMonitorCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = thermal_lidar_calibration::test_support::tempDir("tlc_cli_monitor_");
    generate("stable", "");
    generate("bump", " --extrinsic-change-at 60 --extrinsic-change 0.5,3");
  }
  static void generate(const std::string& name, const std::string& extra) {
    const RunResult gen = tlc_cli_test::runTool(
        MAKE_SYNTHETIC_BAG_EXE,
        "--seed 2 --frames 2400 --output '" + dir_ + "/" + name + ".bag' --truth '" + dir_ + "/" + name +
            ".truth.yaml'" + extra,
        dir_);
    ASSERT_EQ(gen.exit_code, 0) << gen.err;
  }
  // Watches `name`.bag against the extrinsic it starts with (its truth file's top-level keys).
  // `extra`: more options; the result is `name``suffix`.yaml.
  static RunResult monitor(const std::string& name, const std::string& extra = "", const std::string& suffix = "") {
    return tlc_cli_test::runTool(CALIBRATE_BAG_EXE,
                                 "--bag '" + dir_ + "/" + name + ".bag' --monitor --reference '" + dir_ + "/" +
                                     name + ".truth.yaml' --output '" + dir_ + "/" + name + suffix + ".yaml'" + extra,
                                 dir_);
  }
  static std::string dir_;
};
std::string CalibrateBagMonitorCli::dir_;

TEST_F(CalibrateBagMonitorCli, ABumpIsConfirmedAfterItHappensWithTheTimelineBeside) {
  const RunResult r = monitor("bump");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::printf("%s", r.out.c_str());
  const YAML::Node truth = YAML::LoadFile(dir_ + "/bump.truth.yaml");
  const double at = truth["extrinsic_change"]["at_stamp"].as<double>();
  const YAML::Node y = YAML::LoadFile(dir_ + "/bump.yaml");
  for (const char* key : {"rotation_vector", "translation", "rotation_matrix", "quaternion_xyzw", "loss",
                          "pairs_used", "pairs_collected", "lidar_frame", "camera_frame"}) {
    EXPECT_TRUE(y[key]) << key;
  }
  ASSERT_TRUE(y["drift"]);
  EXPECT_EQ(y["drift"]["state"].as<std::string>(), "ERROR");
  // Issue 23: the watch pairs the frames the count rule passed over, at the reference.
  const YAML::Node by_rule = y["drift"]["pairs_by_rule"];
  EXPECT_GT(by_rule["association"].as<int>(), 0);
  EXPECT_EQ(by_rule["counts"].as<int>() + by_rule["association"].as<int>(), y["drift"]["pairs"].as<int>());
  EXPECT_NE(r.out.find("pairs by rule    counts "), std::string::npos) << r.out;
  // A steady drive cannot tell a latency change from a shift along the travel: never timing.
  EXPECT_EQ(y["drift"]["timing_state"].as<std::string>(), "OK");
  ASSERT_FALSE(y["drift"]["first_error_stamp"].IsNull());
  EXPECT_GE(y["drift"]["first_error_stamp"].as<double>(), at);
  if (!y["drift"]["first_warn_stamp"].IsNull()) EXPECT_GE(y["drift"]["first_warn_stamp"].as<double>(), at);
  EXPECT_NEAR(y["drift"]["rotation_change_deg"].as<double>(), 0.5, 0.2);
  // The new extrinsic (fitted on the pairs since the change) against the new truth: the issue's
  // 0.15 deg / 2 cm (measured 0.027 deg, 1.0 cm; confirmed 21.6 s, ~18 kept pairs, after the bump).
  const YAML::Node after = truth["extrinsic_change"]["after"];
  Eigen::Matrix3d R_truth, R_fit;
  for (int i = 0; i < 9; ++i) {
    R_truth(i / 3, i % 3) = after["rotation_matrix"][i].as<double>();
    R_fit(i / 3, i % 3) = y["rotation_matrix"][i].as<double>();
  }
  const double angle_deg = Eigen::AngleAxisd(R_truth.transpose() * R_fit).angle() * 180.0 / M_PI;
  Eigen::Vector3d t_truth, t_fit;
  for (int i = 0; i < 3; ++i) {
    t_truth[i] = after["translation"][i].as<double>();
    t_fit[i] = y["translation"][i].as<double>();
  }
  EXPECT_LT(angle_deg, 0.15);
  EXPECT_LT((t_fit - t_truth).norm(), 0.02);
  EXPECT_LE(y["drift"]["first_error_stamp"].as<double>(), at + 35.0) << "confirmed too late";
  // The new fit says which motion it is and how far its pairs pin it down, in the file and the
  // summary.
  const YAML::Node candidate = y["drift"]["candidate"];
  ASSERT_TRUE(candidate);
  EXPECT_TRUE(candidate["model"]);
  ASSERT_TRUE(candidate["uncertainty"]);
  for (const char* key : {"rotation_deg", "translation_cm"}) {
    ASSERT_EQ(candidate["uncertainty"][key].size(), 3u) << key;
    for (int i = 0; i < 3; ++i) EXPECT_GT(candidate["uncertainty"][key][i].as<double>(), 0.0) << key;
  }
  EXPECT_NE(r.out.find("95 % intervals"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("new fit          " + candidate["model"].as<std::string>()), std::string::npos)
      << r.out;

  std::ifstream csv(dir_ + "/bump.drift.csv");
  std::string header, row;
  std::getline(csv, header);
  EXPECT_EQ(header, "stamp,pairs_in_window,state,rotation_change_deg,translation_change_cm,loss_reference,loss_fit,pairs_seen,p_value,held_out_pairs,image_shift_px,pairs_used,changed,"
                    "offset_x_px,offset_y_px,offset_p_value_x,offset_p_value_y,offset_pairs,timing_state,timing_change_ms");
  int rows = 0, errors = 0;
  while (std::getline(csv, row)) {
    ++rows;
    const bool error = row.find(",ERROR,") != std::string::npos;
    errors += error;
    // The evidence columns: the first ERROR row is a changed test (ERROR only follows changed
    // tests), and one of its tests' p-values (held-out, offset across, offset down) is below
    // monitor_significance.
    if (error && errors == 1) {
      std::vector<std::string> cells;
      std::stringstream fields(row);
      for (std::string cell; std::getline(fields, cell, ',');) cells.push_back(cell);
      ASSERT_EQ(cells.size(), 20u) << row;
      EXPECT_EQ(cells[18], "OK") << "a bump of the extrinsic read as a timing change: " << row;
      EXPECT_EQ(cells[12], "1") << row;
      EXPECT_LT(std::min({std::stod(cells[8]), std::stod(cells[15]), std::stod(cells[16])}), 0.01)
          << row;
      EXPECT_GT(std::stoi(cells[17]), 0) << row;
    }
  }
  EXPECT_GT(rows, 5);
  EXPECT_GT(errors, 0);
  const cv::Mat png = cv::imread(dir_ + "/bump.drift.png");
  ASSERT_FALSE(png.empty());
  EXPECT_EQ(png.cols, 1000);
  EXPECT_EQ(png.rows, 600);
  cv::Scalar mean, stddev;
  cv::meanStdDev(png, mean, stddev);
  EXPECT_GT(stddev[0] + stddev[1] + stddev[2], 10.0) << "a blank plot";
}

TEST_F(CalibrateBagMonitorCli, AStableDriveStaysOkPairedByCountsOrByAssociation) {
  const RunResult r = monitor("stable");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const YAML::Node y = YAML::LoadFile(dir_ + "/stable.yaml");
  EXPECT_EQ(y["drift"]["state"].as<std::string>(), "OK");
  EXPECT_TRUE(y["drift"]["first_warn_stamp"].IsNull()) << y["drift"]["first_warn_stamp"];
  EXPECT_TRUE(y["drift"]["first_error_stamp"].IsNull());
  {
    std::ofstream config(dir_ + "/counts.yaml");
    config << "pairing: counts\n";
  }
  const RunResult counts = monitor("stable", " --config '" + dir_ + "/counts.yaml'", ".counts");
  ASSERT_EQ(counts.exit_code, 0) << counts.err;
  const YAML::Node c = YAML::LoadFile(dir_ + "/stable.counts.yaml")["drift"];
  EXPECT_EQ(c["state"].as<std::string>(), "OK");
  EXPECT_EQ(c["pairs_by_rule"]["association"].as<int>(), 0);
  EXPECT_EQ(c["pairs_by_rule"]["counts"].as<int>(), c["pairs"].as<int>());
  // The count rule's pairs are the same either way; association adds to them.
  EXPECT_EQ(y["drift"]["pairs_by_rule"]["counts"].as<int>(), c["pairs"].as<int>());
  EXPECT_GT(y["drift"]["pairs"].as<int>(), c["pairs"].as<int>());
}

TEST_F(CalibrateBagMonitorCli, MonitorWithoutAReferenceIsAUsageError) {
  const RunResult r = tlc_cli_test::runTool(
      CALIBRATE_BAG_EXE, "--bag '" + dir_ + "/stable.bag' --monitor --output '" + dir_ + "/x.yaml'", dir_);
  const std::string e = tlc_cli_test::expectOneLineError(r, "calibrate_bag: error: ", 2);
  EXPECT_NE(e.find("--monitor needs --reference"), std::string::npos) << e;
}

}  // namespace
