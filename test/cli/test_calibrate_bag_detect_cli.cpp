// calibrate_bag --detect: a bag of raw topics (make_synthetic_bag --raw: full-density
// /lidar/points and a radiometric mono16 image) calibrates without any mask or cluster topic,
// and the errors around it name the flag to use.

#include "cli_run.hpp"
#include "../support/test_files.hpp"

#include <gtest/gtest.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <yaml-cpp/yaml.h>

#include <fstream>
#include <string>


namespace {

using tlc_cli_test::RunResult;

class CalibrateBagDetectCli : public ::testing::Test {
 protected:
  // One raw drive for the whole suite (~45k points per scan, ~500 MB: generated once, ~8 s). The
  // drive of docs/validation/accuracy.md (1200 frames, seed 1): 60 s drives are too short to hold the figure
  // on every seed (with the parked vehicles and animals, this seed's first 60 s gave 0.19 deg).
  static constexpr const char* kFrames = "1200";
  static void SetUpTestSuite() {
    dir_ = thermal_lidar_calibration::test_support::tempDir("tlc_cli_detect_");
    raw_bag_ = dir_ + "/raw.bag";
    truth_ = dir_ + "/truth.yaml";
    const RunResult gen = tlc_cli_test::runTool(
        MAKE_SYNTHETIC_BAG_EXE,
        std::string("--raw --frames ") + kFrames + " --seed 1 --output '" + raw_bag_ + "' --truth '" + truth_ + "'",
        dir_);
    ASSERT_EQ(gen.exit_code, 0) << gen.err;
  }

  static RunResult run(const std::string& args) {
    return tlc_cli_test::runTool(CALIBRATE_BAG_EXE, args, dir_);
  }
  static std::string expectOneLineError(const RunResult& r) {
    return tlc_cli_test::expectOneLineError(r, "calibrate_bag: error: ");
  }

  // The first `frames` frames of the raw drive, only the raw sensor topics (what a tractor
  // records): no mask, no clusters.
  static std::string rawOnlyBag(int frames) {
    const std::string path = dir_ + "/raw_only.bag";
    rosbag::Bag in(raw_bag_, rosbag::bagmode::Read), out(path, rosbag::bagmode::Write);
    int images = 0;
    for (const rosbag::MessageInstance& m : rosbag::View(
             in, rosbag::TopicQuery({"/thermal/image_raw", "/thermal/camera_info", "/lidar/points"}))) {
      if (m.getTopic() == "/thermal/image_raw" && ++images > frames) break;
      out.write(m.getTopic(), m.getTime(), m);
    }
    return path;
  }

  static std::string dir_, raw_bag_, truth_;
};
std::string CalibrateBagDetectCli::dir_, CalibrateBagDetectCli::raw_bag_, CalibrateBagDetectCli::truth_;

// A default run from raw topics (sun-heated posts, parked vehicles and animals as warm
// confounders, image noise) on a fixed 120 s drive: within the 0.15 deg and 3 cm of the
// truth (docs/validation/accuracy.md, "From raw sensors": clean seed 1, 0.020 deg, 0.66 cm; the
// ideal topics of the same drive give 0.019 deg, 0.49 cm). Over drives the spread is wider and
// short drives can fail.
TEST_F(CalibrateBagDetectCli, CalibratesFromRawTopicsNearTheTruth) {
  const std::string out = dir_ + "/detect.yaml";
  const RunResult r = run("--bag '" + raw_bag_ + "' --detect --output '" + out + "' --truth '" + truth_ + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const YAML::Node y = YAML::LoadFile(out);
  EXPECT_GE(y["pairs_collected"].as<int>(), 20);
  std::printf("[ detect ] %d pairs kept, %d used; rotation error %.4f deg, translation error %.2f cm\n",
              y["pairs_collected"].as<int>(), y["pairs_used"].as<int>(),
              y["truth"]["rotation_error_deg"].as<double>(),
              100.0 * y["truth"]["translation_error_m"].as<double>());
  EXPECT_LT(y["truth"]["rotation_error_deg"].as<double>(), 0.15);
  EXPECT_LT(y["truth"]["translation_error_m"].as<double>(), 0.03);
}

TEST_F(CalibrateBagDetectCli, RawTopicsWithoutDetectNameTheFlag) {
  const RunResult r = run("--bag '" + rawOnlyBag(20) + "' --output '" + dir_ + "/x.yaml' --quiet");
  const std::string e = expectOneLineError(r);
  EXPECT_NE(e.find("has raw /lidar/points but no /thermal/human_mask"), std::string::npos) << e;
  EXPECT_NE(e.find("pass --detect"), std::string::npos) << e;
}

TEST_F(CalibrateBagDetectCli, DetectWithoutThePointsTopicNamesTheFlag) {
  const RunResult r = run("--bag '" + rawOnlyBag(20) + "' --detect --points-topic /velodyne_points --output '" +
                          dir_ + "/x.yaml' --quiet");
  const std::string e = expectOneLineError(r);
  EXPECT_NE(e.find("topic /velodyne_points is not in bag"), std::string::npos) << e;
  EXPECT_NE(e.find("--points-topic"), std::string::npos) << e;
}

TEST_F(CalibrateBagDetectCli, BadDetectorKeyIsOneLineNamingIt) {
  std::ofstream(dir_ + "/bad.yaml") << "thermal_input_flip: sideways\n";
  const RunResult r = run("--bag '" + rawOnlyBag(20) + "' --detect --config '" + dir_ +
                          "/bad.yaml' --output '" + dir_ + "/x.yaml' --quiet");
  const std::string e = expectOneLineError(r);
  EXPECT_NE(e.find("thermal_input_flip"), std::string::npos) << e;
  EXPECT_NE(e.find("sideways"), std::string::npos) << e;
}

// A LiDAR bearing window much wider than the camera's view makes wrong pairs: said before the
// bag is read, in one line, and the run goes on (it is the user's setting).
TEST_F(CalibrateBagDetectCli, ABearingWindowWiderThanTheCameraIsWarnedAbout) {
  std::ofstream(dir_ + "/wide.yaml") << "lidar_min_azimuth_deg: -60\nlidar_max_azimuth_deg: 60\n";
  const RunResult wide = run("--bag '" + rawOnlyBag(20) + "' --detect --config '" + dir_ + "/wide.yaml' --output '" +
                             dir_ + "/wide_out.yaml' --quiet");
  EXPECT_NE(wide.err.find("120 deg bearing window"), std::string::npos) << wide.err;
  EXPECT_NE(wide.err.find("camera sees 45 deg"), std::string::npos) << wide.err;
  const RunResult fitting = run("--bag '" + rawOnlyBag(20) + "' --detect --output '" + dir_ + "/fit_out.yaml' --quiet");
  EXPECT_EQ(fitting.err.find("bearing window"), std::string::npos) << fitting.err;
}

// An upside-down camera (FieldSAFE's A65 reportedly stores its images so) without the flip
// finds people in the wrong place: nothing fits. The flip is applied before everything else.
TEST_F(CalibrateBagDetectCli, AFlippedImageIsRefusedOrPoorWithoutTheFlipAndFineWithIt) {
  std::ofstream(dir_ + "/flip.yaml") << "thermal_input_flip: vertical\n";
  // The raw drive itself is upright: flipping it must make the result worse, not better.
  const RunResult flipped = run("--bag '" + raw_bag_ + "' --detect --config '" + dir_ +
                                "/flip.yaml' --output '" + dir_ + "/flipped.yaml' --truth '" + truth_ + "' --quiet");
  if (flipped.exit_code == 0) {
    const YAML::Node y = YAML::LoadFile(dir_ + "/flipped.yaml");
    EXPECT_GT(y["truth"]["rotation_error_deg"].as<double>(), 1.0) << "a flip made no difference";
  } else {
    expectOneLineError(flipped);
  }
}

}  // namespace
