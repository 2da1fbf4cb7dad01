// calibrate_bag end to end: one test per bad input (one-line error, non-zero exit, no crash) and
// positive runs on small bags written here with the rosbag C++ API.

#include "bag_fixture.hpp"
#include "cli_run.hpp"
#include "../support/test_files.hpp"

#include "thermal_lidar_calibration/ros/dataset_bag.hpp"
#include "thermal_lidar_calibration/app/files/result_file.hpp"

#include <gtest/gtest.h>
#include <ros/time.h>
#include <rosbag/bag.h>
#include <std_msgs/String.h>
#include <yaml-cpp/yaml.h>

#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>


namespace {

using tlc_cli_test::BagSpec;

using tlc_cli_test::RunResult;
using tlc_cli_test::readFile;

class CalibrateBagCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = thermal_lidar_calibration::test_support::tempDir("tlc_cli_");
    // A smaller optimizer than Table 1 (enough for these clean bags); every frame a candidate.
    std::ofstream(dir_ + "/fast.yaml") << "population_size: 150\nmax_iterations: 80\n"
                                          "skip_frames: 0\nseed: 3\n";
  }

  std::string bag(const BagSpec& spec, const std::string& name = "in.bag") {
    const std::string path = dir_ + "/" + name;
    tlc_cli_test::writeBag(path, spec);
    return path;
  }

  RunResult run(const std::string& args) { return tlc_cli_test::runTool(CALIBRATE_BAG_EXE, args, dir_); }

  static std::string expectOneLineError(const RunResult& r, int code = 1) {
    return tlc_cli_test::expectOneLineError(r, "calibrate_bag: error: ", code);
  }

  std::string common() const { return "--output '" + dir_ + "/out.yaml' --quiet "; }

  std::string dir_;
};

TEST_F(CalibrateBagCli, NoSuchBag) {
  const RunResult r = run("--bag '" + dir_ + "/missing.bag' " + common());
  const std::string e = expectOneLineError(r);
  EXPECT_NE(e.find("no such file"), std::string::npos) << e;
}

TEST_F(CalibrateBagCli, CorruptFileIsNotABag) {
  std::ofstream(dir_ + "/corrupt.bag") << "this is not a bag\n" << std::string(5000, 'x');
  const RunResult r = run("--bag '" + dir_ + "/corrupt.bag' " + common());
  const std::string e = expectOneLineError(r);
  EXPECT_NE(e.find("as a ROS 1 bag"), std::string::npos) << e;
}

TEST_F(CalibrateBagCli, TruncatedBag) {
  BagSpec spec;
  spec.frames = 6;
  const std::string path = bag(spec);
  const std::string data = readFile(path);
  std::ofstream(dir_ + "/cut.bag", std::ios::binary) << data.substr(0, data.size() / 2);
  const RunResult r = run("--bag '" + dir_ + "/cut.bag' " + common());
  const std::string e = expectOneLineError(r);
  EXPECT_NE(e.find("is damaged or truncated"), std::string::npos) << e;
}

TEST_F(CalibrateBagCli, TopicNotInBagListsTheBagTopics) {
  BagSpec spec;
  spec.frames = 4;
  const RunResult r = run("--bag '" + bag(spec) + "' --mask-topic /seg/masks " + common());
  const std::string e = expectOneLineError(r);
  EXPECT_NE(e.find("topic /seg/masks is not in bag"), std::string::npos) << e;
  EXPECT_NE(e.find("/thermal/human_mask (sensor_msgs/Image, 4)"), std::string::npos) << e;
  EXPECT_NE(e.find("--mask-topic"), std::string::npos) << e;
}

TEST_F(CalibrateBagCli, WrongMaskEncodingIsCountedAndReported) {
  BagSpec spec;
  spec.frames = 8;
  spec.mask_encoding = "rgb8";
  const RunResult r = run("--bag '" + bag(spec) + "' --config '" + dir_ + "/fast.yaml' " + common());
  const std::string e = expectOneLineError(r);
  EXPECT_NE(e.find("no pairs kept"), std::string::npos) << e;
  EXPECT_NE(e.find("bad 8"), std::string::npos) << e;
  EXPECT_NE(e.find("rgb8"), std::string::npos) << e;
  EXPECT_NE(r.err.find("calibrate_bag: warning: bad frame"), std::string::npos) << r.err;
}

TEST_F(CalibrateBagCli, CloudWithoutLabel) {
  BagSpec spec;
  spec.frames = 6;
  spec.label_field = false;
  const RunResult r = run("--bag '" + bag(spec) + "' --config '" + dir_ + "/fast.yaml' " + common());
  const std::string e = expectOneLineError(r);
  EXPECT_NE(e.find("no 'label' field (fields: x, y, z, intensity)"), std::string::npos) << e;
}

TEST_F(CalibrateBagCli, ImageSizeDisagreesWithCameraInfo) {
  BagSpec spec;
  spec.frames = 6;
  spec.camera_info_width = 320;
  const RunResult r = run("--bag '" + bag(spec) + "' --config '" + dir_ + "/fast.yaml' " + common());
  const std::string e = expectOneLineError(r);
  EXPECT_NE(e.find("mask is 160x128 but camera_info says 320x128"), std::string::npos) << e;
}

TEST_F(CalibrateBagCli, NoCameraInfoAndNoFlag) {
  BagSpec spec;
  spec.frames = 4;
  spec.write_camera_info = false;
  const RunResult r = run("--bag '" + bag(spec) + "' " + common());
  const std::string e = expectOneLineError(r);
  EXPECT_NE(e.find("pass --camera-info FILE.yaml"), std::string::npos) << e;
}

TEST_F(CalibrateBagCli, ZeroPairsKeptPrintsRejectionCounts) {
  BagSpec spec;
  spec.frames = 10;
  spec.people_in_mask = false;
  const RunResult r = run("--bag '" + bag(spec) + "' --config '" + dir_ + "/fast.yaml' " + common());
  const std::string e = expectOneLineError(r);
  EXPECT_NE(e.find("no pairs kept from 10 synchronized frames (kept 0; rejected: unequal 10"),
            std::string::npos)
      << e;
}

TEST_F(CalibrateBagCli, EmptyBag) {
  { rosbag::Bag empty(dir_ + "/empty.bag", rosbag::bagmode::Write); }
  const RunResult r = run("--bag '" + dir_ + "/empty.bag' " + common());
  const std::string e = expectOneLineError(r);
  EXPECT_NE(e.find("is empty"), std::string::npos) << e;
}

// An unwritable --output is refused before the bag is read, not after the optimization.
TEST_F(CalibrateBagCli, OutputInAMissingDirectoryIsRefusedAtOnce) {
  BagSpec spec;
  spec.frames = 4;
  const RunResult r =
      run("--bag '" + bag(spec) + "' --output '" + dir_ + "/no/such/dir/out.yaml' --quiet");
  const std::string e = expectOneLineError(r);
  EXPECT_NE(e.find("--output: directory " + dir_ + "/no/such/dir of"), std::string::npos) << e;
  EXPECT_NE(e.find("does not exist"), std::string::npos) << e;
}

// Bad frames are said as the node says them (BadFrameReporter): one line per kind of fault and
// 5 s of the bag's own time, the next counting the rest; before, each distinct text (sizes in
// it) was a new warning, up to 5.
TEST_F(CalibrateBagCli, BadFramesAreSaidOncePerKindAndFiveSecondsOfBagTime) {
  BagSpec spec;
  spec.frames = 120;  // 12 s at 10 Hz, every frame's mask disagreeing with camera_info
  spec.camera_info_width = 200;
  const RunResult r = run("--bag '" + bag(spec) + "' --output '" + dir_ + "/out.yaml'");
  expectOneLineError(r);
  int lines = 0;
  std::istringstream err(r.err);
  std::string line, last_bad;
  while (std::getline(err, line)) {
    if (line.find("warning: bad frame at") != std::string::npos) {
      ++lines;
      last_bad = line;
    }
  }
  EXPECT_EQ(lines, 3) << r.err;  // at 0 s, 5 s and 10 s of the bag
  EXPECT_NE(last_bad.find("more like it in the last 5 s"), std::string::npos) << last_bad;
}

TEST_F(CalibrateBagCli, UsageErrorsExitWithTwo) {
  expectOneLineError(run(""), 2);
  expectOneLineError(run("--bag x.bag --output y.yaml --algorithm 3"), 2);
  expectOneLineError(run("--bag x.bag --output y.yaml --frobnicate"), 2);
  const RunResult help = run("--help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.out.find("usage: calibrate_bag"), std::string::npos);
}

TEST_F(CalibrateBagCli, BadConfigValueNamesKeyValueAndRange) {
  BagSpec spec;
  spec.frames = 4;
  std::ofstream(dir_ + "/bad.yaml") << "population_size: -3\n";
  const RunResult r = run("--bag '" + bag(spec) + "' --config '" + dir_ + "/bad.yaml' " + common());
  const std::string e = expectOneLineError(r);
  EXPECT_NE(e.find("parameter 'population_size' = -3: must be an integer in [2, 100000]"),
            std::string::npos)
      << e;
}

TEST_F(CalibrateBagCli, BadRingAliasTurnsNamesKeyValueAndRange) {
  BagSpec spec;
  spec.frames = 4;
  for (const std::string value : {"-1", "6", "two"}) {
    std::ofstream(dir_ + "/bad.yaml") << "refine_ring_alias_turns: " << value << "\n";
    const RunResult r = run("--bag '" + bag(spec) + "' --config '" + dir_ + "/bad.yaml' " + common());
    const std::string e = expectOneLineError(r);
    EXPECT_NE(e.find("parameter 'refine_ring_alias_turns' = " + std::string(value == "two" ? "'two'" : value) +
                     ": must be an integer in [0, 5]"),
              std::string::npos)
        << e;
  }
}

TEST_F(CalibrateBagCli, CalibratesASyntheticBag) {
  BagSpec spec;
  const std::string truth = dir_ + "/truth.yaml";
  tlc_cli_test::writeTruthFile(truth);
  std::ofstream(dir_ + "/fast.yaml", std::ios::app) << "typo_key: 1\n";
  const RunResult r = run("--bag '" + bag(spec) + "' --config '" + dir_ + "/fast.yaml' --output '" +
                          dir_ + "/out.yaml' --truth '" + truth + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("unknown keys ignored (possible typo): typo_key"), std::string::npos)
      << r.err;
  EXPECT_NE(r.out.find("rosrun tf2_ros static_transform_publisher"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("velodyne thermal_optical"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("rotation error"), std::string::npos) << r.out;

  const YAML::Node y = YAML::LoadFile(dir_ + "/out.yaml");
  EXPECT_EQ(y["lidar_frame"].as<std::string>(), "velodyne");
  EXPECT_EQ(y["camera_frame"].as<std::string>(), "thermal_optical");
  EXPECT_EQ(y["pairs_collected"].as<int>(), 40);
  EXPECT_GE(y["pairs_used"].as<int>(), 30);
  EXPECT_LT(y["loss"].as<double>(), 1.0);
  Eigen::Vector3d r_vec, t_vec;
  for (int i = 0; i < 3; ++i) {
    r_vec[i] = y["rotation_vector"][i].as<double>();
    t_vec[i] = y["translation"][i].as<double>();
  }
  const Eigen::Matrix3d R = Eigen::AngleAxisd(r_vec.norm(), r_vec.normalized()).toRotationMatrix();
  const double angle_deg =
      Eigen::AngleAxisd(R.transpose() * tlc_cli_test::truthRotation()).angle() * 180.0 / M_PI;
  EXPECT_LT(angle_deg, 1.0);
  EXPECT_LT((t_vec - tlc_cli_test::truthTranslation()).norm(), 0.10);
  // --truth also goes into the result file, so scripts need not parse the summary.
  ASSERT_TRUE(y["truth"]) << "no truth block";
  EXPECT_EQ(y["truth"]["file"].as<std::string>(), truth);
  EXPECT_NEAR(y["truth"]["rotation_error_deg"].as<double>(), angle_deg, 1e-6);
  EXPECT_NEAR(y["truth"]["translation_error_m"].as<double>(),
              (t_vec - tlc_cli_test::truthTranslation()).norm(), 1e-6);
  EXPECT_GE(y["truth"]["loss"].as<double>(), 0.0);
  // max_iterations 80 < refine_evolution_generations: no shortened evolution, nothing run twice.
  EXPECT_FALSE(y["evolution"]["full_length"].as<bool>());
  EXPECT_EQ(r.out.find("evolution run to max_iterations"), std::string::npos) << r.out;
}

// refine_evolution_min_share 1 asks for every pair within threshold_sample_px of the fit after
// the one-generation evolution, and a threshold of 0.01 px with a one-evaluation refinement
// leaves some outside it: the fit after the full length runs too, and the summary and the result
// file say so.
TEST_F(CalibrateBagCli, AShortenedEvolutionsFailedFitIsSaidAndRunToItsFullLength) {
  BagSpec spec;
  std::ofstream(dir_ + "/fast.yaml", std::ios::app)
      << "refine_evolution_generations: 1\nrefine_evolution_min_share: 1.0\nthreshold_sample_px: 0.01\n"
         // On this bag's exact clusters a full refinement can lay every pair within 0.01 px.
         "refine_max_evaluations: 1\n";
  const RunResult r = run("--bag '" + bag(spec) + "' --config '" + dir_ + "/fast.yaml' --output '" +
                          dir_ + "/out.yaml' --algorithm 1");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("evolution run to max_iterations: the shortened run's fit failed Algorithm 2's test"),
            std::string::npos) << r.out;
  EXPECT_TRUE(YAML::LoadFile(dir_ + "/out.yaml")["evolution"]["full_length"].as<bool>());
}

TEST_F(CalibrateBagCli, NonFinitePointsAreDroppedNotAnError) {
  BagSpec spec;
  spec.nonfinite_every = 10;
  const RunResult r = run("--bag '" + bag(spec) + "' --config '" + dir_ + "/fast.yaml' --output '" +
                          dir_ + "/out.yaml' --algorithm 1 --refine none");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("non-finite points dropped"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("non-finite points dropped 0"), std::string::npos) << r.out;
}

TEST_F(CalibrateBagCli, CameraInfoFileReplacesTheBagTopic) {
  BagSpec spec;
  spec.write_camera_info = false;
  spec.frames = 24;
  tlc_cli_test::writeCameraInfoYaml(spec, dir_ + "/cam.yaml");
  const RunResult r = run("--bag '" + bag(spec) + "' --config '" + dir_ + "/fast.yaml' --output '" +
                          dir_ + "/out.yaml' --camera-info '" + dir_ +
                          "/cam.yaml' --algorithm 1 --refine none --quiet");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(YAML::LoadFile(dir_ + "/out.yaml")["rotation_vector"]);
}

// The generator's bag (ray-cast people, fieldsafe rig): the tool runs end to end on it and gets
// close to the truth with the default (Table 1) parameters.
TEST_F(CalibrateBagCli, CalibratesAMakeSyntheticBagBag) {
  const std::string path = dir_ + "/syn.bag";
  const std::string gen = std::string("'") + MAKE_SYNTHETIC_BAG_EXE + "' --output '" + path +
                          "' --frames 200 --seed 2 >/dev/null 2>&1";
  ASSERT_EQ(std::system(gen.c_str()), 0) << gen;
  const RunResult r = run("--bag '" + path + "' --output '" + dir_ + "/out.yaml' --truth '" +
                          path + ".truth.yaml'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("rotation error"), std::string::npos) << r.out;
  const thermal_lidar_calibration::Extrinsic result =
      thermal_lidar_calibration::readExtrinsicFile(dir_ + "/out.yaml");
  const thermal_lidar_calibration::Extrinsic truth =
      thermal_lidar_calibration::readExtrinsicFile(path + ".truth.yaml");
  EXPECT_LT(thermal_lidar_calibration::rotationErrorRad(result, truth) * 180.0 / M_PI, 2.0);
  EXPECT_LT(thermal_lidar_calibration::translationErrorM(result, truth), 0.30);
  const YAML::Node y = YAML::LoadFile(dir_ + "/out.yaml");
  EXPECT_GE(y["pairs_used"].as<int>(), 20);
}

}  // namespace

int main(int argc, char** argv) {
  ros::Time::init();
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}

TEST_F(CalibrateBagCli, DatasetBagFromTheNodeIsNotSkippedAgain) {
  // A calibration_node dataset bag: every frame was already kept by the node's gate.
  BagSpec spec;
  const std::string path = bag(spec, "dataset.bag");
  {
    rosbag::Bag b(path, rosbag::bagmode::Append);
    std_msgs::String marker;
    marker.data = "pair kept by calibration_node (already gated)";
    for (int f = 0; f < spec.frames; ++f) {
      b.write(thermal_lidar_calibration::ros_io::DatasetBagTopics::kMarker,
              ros::Time(1000.0 + 0.1 * f), marker);
    }
  }
  // The default skip rule (3) is in force: without the marker 3 of 4 frames would be skipped.
  std::ofstream(dir_ + "/skip.yaml") << "population_size: 150\nmax_iterations: 80\nseed: 3\n";
  const RunResult r = run("--bag '" + path + "' --config '" + dir_ + "/skip.yaml' --output '" +
                          dir_ + "/out.yaml'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("dataset bag: its pairs and association candidates as the node kept them"), std::string::npos)
      << r.err;
  EXPECT_EQ(YAML::LoadFile(dir_ + "/out.yaml")["pairs_collected"].as<int>(), spec.frames);
}

namespace {

// Turns a bag of `frames` frames (BagSpec: 0.1 s apart from t = 1000 s) into a node's dataset bag
// whose every frame was held as an association candidate, every 4th frame offered.
void markAllAsCandidates(const std::string& path, int frames) {
  rosbag::Bag b(path, rosbag::bagmode::Append);
  for (int f = 0; f < frames; ++f) {
    std_msgs::String marker;
    marker.data = thermal_lidar_calibration::ros_io::datasetMarkerText({true, static_cast<std::uint64_t>(4 * f)});
    b.write(thermal_lidar_calibration::ros_io::DatasetBagTopics::kCandidateMarker, ros::Time(1000.0 + 0.1 * f), marker);
  }
}

}  // namespace

// Frames a node held as association candidates come back as candidates at their place (the
// node's result again: test_node_resume.py); one that today's count rule keeps (here the
// one-person frames, H_max 1) becomes a pair of that rule.
TEST_F(CalibrateBagCli, ADatasetBagsCandidatesAreReadAsTheNodeHeldThem) {
  BagSpec spec;  // one person in even frames, two in odd ones
  const std::string path = bag(spec, "candidates.bag");
  markAllAsCandidates(path, spec.frames);
  std::ofstream(dir_ + "/h1.yaml") << "population_size: 150\nmax_iterations: 80\nseed: 3\nmax_people: 1\nuncertainty: false\n";
  const RunResult r = run("--bag '" + path + "' --config '" + dir_ + "/h1.yaml' --output '" + dir_ + "/out.yaml'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const YAML::Node y = YAML::LoadFile(dir_ + "/out.yaml");
  EXPECT_EQ(y["pairs_by_rule"]["counts"].as<int>(), spec.frames / 2) << r.err;
  EXPECT_EQ(y["association"]["candidate_frames"].as<int>(), spec.frames / 2) << r.err;
}

// A dataset bag whose frames were all held as association candidates (today's count rule keeps
// none of them: here every cluster is below min_points_per_cluster) has nothing for the first
// fit, which association needs: one line that says so, not an empty fit.
TEST_F(CalibrateBagCli, ADatasetBagOfCandidatesAloneIsOneLineSayingTheFirstFitNeedsPairs) {
  BagSpec spec;
  const std::string path = bag(spec, "only_candidates.bag");
  markAllAsCandidates(path, spec.frames);
  std::ofstream(dir_ + "/big.yaml") << "min_points_per_cluster: 100000\n";
  const RunResult r = run("--bag '" + path + "' --config '" + dir_ + "/big.yaml' --output '" + dir_ + "/out.yaml'");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("calibrate_bag: error: no pairs in the dataset bag " + path + ": the dataset bag holds " +
                       std::to_string(spec.frames) + " association candidates but no pair of the count rule, "
                       "which the first fit needs: resume the node (~resume) on more of the drive"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(std::ifstream(dir_ + "/out.yaml").good()) << "no result file from no pairs";
}
