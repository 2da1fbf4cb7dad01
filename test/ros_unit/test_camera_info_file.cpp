// camera_calibration YAML files: the shipped FLIR A65 file, round trips and bad files.

#include "thermal_lidar_calibration/app/files/camera_info_file.hpp"
#include "thermal_lidar_calibration/ros/msg_conversion.hpp"

#include "../support/test_files.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

namespace tlc = thermal_lidar_calibration;
using tlc::loadCameraInfoFile;
using tlc::writeCameraInfoFile;

namespace {

std::string tempDir() { return tlc::test_support::tempDir("tlc_camera_info_"); }

std::string writeText(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
  return path;
}

std::string errorOf(const std::string& path) {
  return tlc::test_support::errorOf([&] { loadCameraInfoFile(path); });
}

}  // namespace

TEST(CameraInfoFile, LoadsTheShippedFlirA65File) {
  // Tests run in test/; the config directory is next to it.
  const tlc::CameraModel m = loadCameraInfoFile("../config/flir_a65_camera_info.yaml");
  EXPECT_EQ(m.width, 640);
  EXPECT_EQ(m.height, 512);
  EXPECT_DOUBLE_EQ(m.fx, 772.41);
  EXPECT_DOUBLE_EQ(m.fy, 772.83);
  EXPECT_DOUBLE_EQ(m.cx, 322.67);
  EXPECT_DOUBLE_EQ(m.cy, 250.66);
  EXPECT_DOUBLE_EQ(m.distortion[0], -0.0496);
  EXPECT_DOUBLE_EQ(m.distortion[1], 0.3632);
  EXPECT_DOUBLE_EQ(m.distortion[4], 0.0);
}

TEST(CameraInfoFile, RoundTrip) {
  tlc::CameraModel m = tlc::CameraModel::fromK(
      320, 256, {400.5, 0.25, 160.0, 0, 401.0, 128.5, 0, 0, 1}, {0.01, -0.02, 0.001, 0.002, 0.0});
  const std::string path = tempDir() + "/cam.yaml";
  writeCameraInfoFile(path, m, "test_cam");
  const tlc::CameraModel back = loadCameraInfoFile(path);
  EXPECT_EQ(back.width, 320);
  EXPECT_EQ(back.height, 256);
  EXPECT_DOUBLE_EQ(back.fx, m.fx);
  EXPECT_DOUBLE_EQ(back.fy, m.fy);
  EXPECT_DOUBLE_EQ(back.cx, m.cx);
  EXPECT_DOUBLE_EQ(back.cy, m.cy);
  EXPECT_DOUBLE_EQ(back.skew, m.skew);
  for (int i = 0; i < 5; ++i) EXPECT_DOUBLE_EQ(back.distortion[i], m.distortion[i]);
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (const char* key : {"image_width", "image_height", "camera_name", "camera_matrix",
                          "distortion_model", "distortion_coefficients", "rectification_matrix",
                          "projection_matrix"}) {
    EXPECT_NE(text.find(key), std::string::npos) << key;
  }
}

TEST(CameraInfoFile, NoDistortionIsAccepted) {
  const std::string dir = tempDir();
  const std::string path = writeText(dir + "/nodist.yaml",
                                     "image_width: 100\nimage_height: 80\n"
                                     "camera_matrix: {rows: 3, cols: 3, data: [100, 0, 50, 0, "
                                     "100, 40, 0, 0, 1]}\n");
  EXPECT_FALSE(loadCameraInfoFile(path).hasDistortion());
}

TEST(CameraInfoFile, BadFilesSayWhatIsWrong) {
  const std::string dir = tempDir();
  EXPECT_NE(errorOf(dir + "/missing.yaml").find("cannot be opened"), std::string::npos);
  EXPECT_NE(errorOf(writeText(dir + "/bad.yaml", "image_width: [1, 2\n")).find("not valid YAML"),
            std::string::npos);
  EXPECT_NE(errorOf(writeText(dir + "/list.yaml", "- 1\n- 2\n")).find("not a YAML map"),
            std::string::npos);
  EXPECT_NE(errorOf(writeText(dir + "/nok.yaml", "image_width: 10\nimage_height: 10\n"))
                .find("missing 'camera_matrix'"),
            std::string::npos);
  EXPECT_NE(errorOf(writeText(dir + "/k8.yaml",
                              "image_width: 10\nimage_height: 10\n"
                              "camera_matrix: {rows: 3, cols: 3, data: [1, 0, 5, 0, 1, 5, 0, 0]}\n"))
                .find("'camera_matrix' says 3x3 but has 8 values"),
            std::string::npos);
  EXPECT_NE(errorOf(writeText(dir + "/w.yaml",
                              "image_width: -4\nimage_height: 10\n"
                              "camera_matrix: [1, 0, 5, 0, 1, 5, 0, 0, 1]\n"))
                .find("'image_width' = -4"),
            std::string::npos);
  EXPECT_NE(errorOf(writeText(dir + "/d.yaml",
                              "image_width: 10\nimage_height: 10\n"
                              "camera_matrix: [1, 0, 5, 0, 1, 5, 0, 0, 1]\n"
                              "distortion_model: equidistant\n"
                              "distortion_coefficients: [0.1, 0.1, 0.0, 0.0]\n"))
                .find("not supported"),
            std::string::npos);
  const std::string e = errorOf(dir + "/missing.yaml");
  EXPECT_EQ(e.rfind("camera info file " + dir + "/missing.yaml: ", 0), 0u) << e;
}

// A camera accepted live is accepted from a file and the other way round: both readers use
// cameraModelFromCalibration, so each case gives the same verdict and the same reason.
TEST(CameraInfoFile, FileAndMessageFollowOneRuleSet) {
  struct Case {
    const char* model;
    std::vector<double> D;
    const char* reason;  // empty: accepted
  };
  const Case cases[] = {{"plumb_bob", {-0.05, 0.36, 0.0, 0.0, 0.0}, ""},
                        {"plumb_bob", {}, ""},
                        {"none", {0, 0, 0, 0, 0}, ""},
                        {"", {}, ""},
                        {"none", {0.1, 0, 0, 0, 0}, "set distortion_model to plumb_bob"},
                        {"plumb_bob", {0.1, 0.1, 0.0, 0.0}, "5 distortion coefficients"},
                        {"equidistant", {0.1, 0.1, 0.0, 0.0}, "not supported"}};
  const std::string dir = tempDir();
  int n = 0;
  for (const Case& c : cases) {
    sensor_msgs::CameraInfo msg;
    msg.width = 640;
    msg.height = 512;
    msg.K = {772.4, 0, 322.7, 0, 772.8, 250.7, 0, 0, 1};
    msg.distortion_model = c.model;
    msg.D = c.D;
    std::string d_text;
    for (std::size_t i = 0; i < c.D.size(); ++i) d_text += (i ? ", " : "") + std::to_string(c.D[i]);
    const std::string path =
        writeText(dir + "/case" + std::to_string(n++) + ".yaml",
                  "image_width: 640\nimage_height: 512\n"
                  "camera_matrix: [772.4, 0, 322.7, 0, 772.8, 250.7, 0, 0, 1]\n"
                  "distortion_model: '" + std::string(c.model) + "'\n"
                  "distortion_coefficients: [" + d_text + "]\n");
    const std::string from_msg =
        tlc::test_support::errorOf([&] { tlc::ros_io::cameraModelFromMsg(msg); });
    const std::string from_file = errorOf(path);
    SCOPED_TRACE(std::string("model '") + c.model + "', " + std::to_string(c.D.size()) + " coefficients");
    if (*c.reason == '\0') {
      EXPECT_EQ(from_msg, "<no exception>");
      EXPECT_EQ(from_file, "<no exception>");
    } else {
      EXPECT_NE(from_msg.find(c.reason), std::string::npos) << from_msg;
      EXPECT_NE(from_file.find(c.reason), std::string::npos) << from_file;
    }
  }
}
