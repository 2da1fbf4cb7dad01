// The detectors' flat parameter keys: a partial YAML file overrides only what it names, bad
// values are refused with the key, the value and the allowed range, and the rules across keys
// hold after loading.

#include "thermal_lidar_calibration/app/parameters/detection_parameters.hpp"
#include "thermal_lidar_calibration/app/parameters/parameter_source.hpp"

#include "../support/test_files.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <set>

namespace thermal_lidar_calibration {
namespace {

using test_support::errorOf;

class DetectionParameterFile : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test_support::tempDir("tlc_detection_params_"); }
  void TearDown() override { std::system(("rm -rf '" + dir_ + "'").c_str()); }
  DetectionParameters load(const std::string& yaml) {
    const std::string path = dir_ + "/params.yaml";
    std::ofstream(path) << yaml;
    return loadDetectionParameters(*makeYamlParameterSource(path));
  }
  std::string dir_;
};

TEST_F(DetectionParameterFile, PartialFileOverridesOnlyWhatItNames) {
  const DetectionParameters p = load("kelvin_per_count: 0.01\nlidar_max_range_m: 25\nthermal_scale: relative\n"
                                     "population_size: 300   # a calibration key: not ours, ignored\n");
  EXPECT_DOUBLE_EQ(p.thermal.kelvin_per_count, 0.01);
  EXPECT_EQ(p.thermal.scale, detection::ThermalScale::kRelative);
  EXPECT_DOUBLE_EQ(p.lidar.person.max_range_m, 25.0);
  const DetectionParameters defaults;
  EXPECT_DOUBLE_EQ(p.thermal.body_min_k, defaults.thermal.body_min_k);
  EXPECT_EQ(p.lidar.ground.sectors, defaults.lidar.ground.sectors);
  EXPECT_DOUBLE_EQ(load("").lidar.person.min_height_m, defaults.lidar.person.min_height_m);
}

TEST_F(DetectionParameterFile, BadValuesNameKeyValueAndRange) {
  EXPECT_EQ(errorOf([&] { load("thermal_min_area_px: 0\n"); }),
            "parameter 'thermal_min_area_px' = 0: must be an integer in [1, 10000000]");
  EXPECT_EQ(errorOf([&] { load("lidar_ground_sectors: 12.5\n"); }),
            "parameter 'lidar_ground_sectors' = 12.5: must be an integer in [4, 3600]");
  EXPECT_NE(errorOf([&] { load("kelvin_per_count: -0.04\n"); }).find("parameter 'kelvin_per_count' = -0.04"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { load("thermal_scale: kelvin\n"); }).find("must be 'auto' or 'relative'"), std::string::npos);
  // Each value in its own range, but not with each other.
  EXPECT_EQ(errorOf([&] { load("lidar_min_height_m: 2.5\n"); }),
            "parameters 'lidar_min_height_m' = 2.5 and 'lidar_max_height_m' = 2.2: lidar_min_height_m must be "
            "below lidar_max_height_m");
  EXPECT_NE(errorOf([&] { load("thermal_min_fill: 0.99\n"); }).find("thermal_min_fill must not exceed thermal_max_fill"),
            std::string::npos);
}

TEST(DetectionParameterTable, EveryKeyOnceAndDescribedWithItsDefault) {
  const auto keys = detectionParameterTable().keys();
  std::set<std::string> unique(keys.begin(), keys.end());
  EXPECT_EQ(unique.size(), keys.size());
  EXPECT_TRUE(unique.count("kelvin_per_count"));
  EXPECT_TRUE(unique.count("kelvin_offset"));
  EXPECT_TRUE(unique.count("lidar_min_points_at_10m"));
  const auto described = describeDetectionParameters(DetectionParameters{});
  ASSERT_EQ(described.size(), keys.size());
  EXPECT_EQ(described.front(), (std::pair<std::string, std::string>{"thermal_input_flip", "none"}));
  EXPECT_EQ(described[1], (std::pair<std::string, std::string>{"kelvin_per_count", "0.04"}));
}

// For calibration the LiDAR counts only people a forward-looking camera can see (the detector
// itself looks all around); a partial file changes only what it names.
TEST_F(DetectionParameterFile, LidarBearingWindowDefaultsToTheForwardView) {
  const DetectionParameters defaults;
  EXPECT_EQ(defaults.lidar.person.min_azimuth_deg, -25.0);
  EXPECT_EQ(defaults.lidar.person.max_azimuth_deg, 25.0);
  EXPECT_EQ(detection::LidarDetectorConfig{}.person.min_azimuth_deg, -180.0);
  const DetectionParameters p = load("thermal_input_flip: vertical\nlidar_max_azimuth_deg: 30\n");
  EXPECT_EQ(p.input_flip, detection::ImageFlip::kVertical);
  EXPECT_EQ(p.lidar.person.min_azimuth_deg, -25.0);
  EXPECT_EQ(p.lidar.person.max_azimuth_deg, 30.0);
  EXPECT_NE(errorOf([&] { load("thermal_input_flip: sideways\n"); }).find("thermal_input_flip"), std::string::npos);
}

TEST(LidarWindowWarning, OnlyWhenTheWindowIsMuchWiderThanTheCamerasView) {
  // A FLIR A65: 640 px across at 772 px focal length, 45 deg of view.
  const CameraModel a65 = CameraModel::fromK(640, 512, {772.0, 0, 320.0, 0, 772.0, 256.0, 0, 0, 1.0}, {});
  DetectionParameters p;  // the default window, +-25 deg
  EXPECT_EQ(lidarWindowWarning(p.lidar.person, a65), "");
  p.lidar.person.min_azimuth_deg = -45.0;
  p.lidar.person.max_azimuth_deg = 45.0;
  const std::string warning = lidarWindowWarning(p.lidar.person, a65);
  EXPECT_NE(warning.find("90 deg bearing window"), std::string::npos) << warning;
  EXPECT_NE(warning.find("camera sees 45 deg"), std::string::npos) << warning;
  EXPECT_EQ(warning.find('\n'), std::string::npos);
  // A wide-angle camera (90 deg) is fine with it.
  const CameraModel wide = CameraModel::fromK(640, 512, {320.0, 0, 320.0, 0, 320.0, 256.0, 0, 0, 1.0}, {});
  EXPECT_EQ(lidarWindowWarning(p.lidar.person, wide), "");
}

}  // namespace
}  // namespace thermal_lidar_calibration
