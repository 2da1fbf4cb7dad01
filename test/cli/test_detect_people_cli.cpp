// detect_people on files this test writes: 8- and 16-bit PNG, 16-bit TIFF, JPEG, grey stored as
// 3 channels, PCD (x y z [intensity]) and KITTI .bin clouds; the printed lines, the written mask
// and clusters, the exit codes, and one-line errors for bad input.

#include "thermal_lidar_calibration/detection_tool/detection_files.hpp"

#include "../support/lidar_scene.hpp"
#include "../support/test_files.hpp"
#include "../support/thermal_scene.hpp"

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <pcl/io/pcd_io.h>
#include <pcl/point_types.h>
#include <sys/wait.h>

#include <fstream>
#include <regex>
#include <sstream>

namespace thermal_lidar_calibration {
namespace {

struct RunResult {
  int exit_code = -1;
  std::string out, err;
};

std::string readText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

int lineCount(const std::string& text) { return static_cast<int>(std::count(text.begin(), text.end(), '\n')); }

class DetectPeopleCli : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test_support::tempDir("tlc_detect_people_"); }
  void TearDown() override {
    if (!std::getenv("TLC_KEEP_TEST_DIR")) std::system(("rm -rf '" + dir_ + "'").c_str());
  }
  RunResult run(const std::string& args) {
    const std::string out = dir_ + "/stdout.txt", err = dir_ + "/stderr.txt";
    const std::string cmd = std::string("'") + DETECT_PEOPLE_EXE + "' " + args + " >'" + out + "' 2>'" + err + "'";
    const int status = std::system(cmd.c_str());
    RunResult r;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = readText(out);
    r.err = readText(err);
    return r;
  }
  std::string path(const std::string& name) const { return dir_ + "/" + name; }

  // A radiometric frame with two people (ids 1 at x~150, 2 at x~430) and an animal.
  cv::Mat twoPeople16() const {
    cv::Mat image = test_support::thermalBackground(cv::Size(320, 256), 288.0, 0.1, 2);
    test_support::drawPerson(image, 80, 40, 110, 307.0, 301.0);
    test_support::drawPerson(image, 230, 70, 80, 306.0, 300.0);
    test_support::drawAnimal(image, 160, 190, 50, 307.0);
    return image;
  }
  // A flat-ground HDL-32E scan with two people and a post.
  test_support::CraftedScan scanWithTwoPeople() const {
    const auto flat = test_support::Terrain::flat();
    return test_support::castScan(synthetic::LidarModel::hdl32e(), flat, test_support::Mount{},
                                  {test_support::personAt(flat, 7.0, 1.0, 1), test_support::personAt(flat, 11.0, -3.0, 2),
                                   test_support::postAt(flat, 9.0, 2.0, 3.0, 0.07)},
                                  0.02, 4, 1);
  }

  std::string dir_;
};

const std::regex kImageLine(R"(person (\d+) bbox (\d+) (\d+) (\d+) (\d+) area (\d+))");
const std::regex kCloudLine(R"(person (\d+) centroid (-?[\d.]+) (-?[\d.]+) (-?[\d.]+) size ([\d.]+) ([\d.]+) ([\d.]+) points (\d+))");

TEST_F(DetectPeopleCli, Radiometric16BitPngGivesMaskAndOneLinePerPerson) {
  ASSERT_TRUE(cv::imwrite(path("frame.png"), twoPeople16()));
  const RunResult r = run("--image " + path("frame.png") + " --mask-out " + path("mask.png") + " --overlay-out " +
                          path("view.png"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(lineCount(r.out), 2) << r.out;
  std::istringstream lines(r.out);
  std::string line;
  const cv::Mat mask = cv::imread(path("mask.png"), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(mask.type(), CV_8UC1);
  ASSERT_EQ(mask.size(), cv::Size(320, 256));
  int id = 0;
  while (std::getline(lines, line)) {
    std::smatch m;
    ASSERT_TRUE(std::regex_match(line, m, kImageLine)) << line;
    EXPECT_EQ(std::stoi(m[1]), ++id);
    EXPECT_EQ(cv::countNonZero(mask == id), std::stoi(m[6])) << "area printed = pixels in the mask";
  }
  EXPECT_EQ(cv::countNonZero(mask > 2), 0);
  EXPECT_FALSE(cv::imread(path("view.png")).empty());
}

TEST_F(DetectPeopleCli, ReadsTiffJpegAnd8BitAndGreyStoredAsColour) {
  const cv::Mat image16 = twoPeople16();
  ASSERT_TRUE(cv::imwrite(path("frame.tiff"), image16));
  EXPECT_EQ(lineCount(run("--image " + path("frame.tiff") + " --mask-out " + path("m1.png")).out), 2);
  // 8-bit renderings (relative mode): PNG, 3 equal channels, JPEG.
  cv::Mat grey;
  image16.convertTo(grey, CV_8U, 1.0 / 16, -7000.0 / 16);
  cv::Mat colour;
  cv::cvtColor(grey, colour, cv::COLOR_GRAY2BGR);
  ASSERT_TRUE(cv::imwrite(path("grey.png"), grey));
  ASSERT_TRUE(cv::imwrite(path("grey3.png"), colour));
  ASSERT_TRUE(cv::imwrite(path("grey.jpg"), grey, {cv::IMWRITE_JPEG_QUALITY, 95}));
  for (const char* name : {"grey.png", "grey3.png", "grey.jpg"}) {
    const RunResult r = run(std::string("--image ") + path(name) + " --mask-out " + path("m.png"));
    EXPECT_EQ(r.exit_code, 0) << name << ": " << r.err;
    EXPECT_EQ(lineCount(r.out), 2) << name << ": " << r.out;
  }
}

TEST_F(DetectPeopleCli, KelvinFlagsAndFlip) {
  // A person only 10 K above a 275 K scene: outside the body band unless the offset says so.
  cv::Mat image = test_support::thermalBackground(cv::Size(320, 256), 275.0, 0.1, 3);
  test_support::drawPerson(image, 100, 30, 120, 287.0, 285.0);
  ASSERT_TRUE(cv::imwrite(path("cold.png"), image));
  EXPECT_EQ(run("--image " + path("cold.png") + " --mask-out " + path("m.png")).out, "no person found\n");
  EXPECT_EQ(lineCount(run("--image " + path("cold.png") + " --mask-out " + path("m.png") + " --kelvin-offset 20").out), 1);
  // Centi-kelvin data (0.01 K/count) read with the right scale.
  cv::Mat centi;
  image.convertTo(centi, CV_16U, 4.0);
  ASSERT_TRUE(cv::imwrite(path("centi.png"), centi));
  EXPECT_EQ(lineCount(run("--image " + path("centi.png") + " --mask-out " + path("m.png") +
                          " --kelvin-per-count 0.01 --kelvin-offset 20").out), 1);
  // --flip vertical on a frame stored upside down: the person is found upright, with the box and
  // the mask of the upright frame (an upside-down person has its neck at the bottom: the
  // segmenter is not meant to see one).
  cv::Mat upside_down;
  cv::flip(image, upside_down, 0);
  ASSERT_TRUE(cv::imwrite(path("upside_down.png"), upside_down));
  const RunResult plain = run("--image " + path("cold.png") + " --mask-out " + path("m.png") + " --kelvin-offset 20");
  const RunResult flipped = run("--image " + path("upside_down.png") + " --mask-out " + path("m.png") +
                                " --kelvin-offset 20 --flip vertical");
  std::smatch a, b;
  ASSERT_TRUE(std::regex_search(plain.out, a, kImageLine));
  ASSERT_TRUE(std::regex_search(flipped.out, b, kImageLine)) << flipped.out;
  EXPECT_EQ(b.str(0), a.str(0));
  EXPECT_EQ(cv::imread(path("m.png"), cv::IMREAD_UNCHANGED).at<std::uint8_t>(90, 100), 1);
}

TEST_F(DetectPeopleCli, ConfigFileSetsTheSameKeysAsTheNodelets) {
  cv::Mat image = test_support::thermalBackground(cv::Size(320, 256), 275.0, 0.1, 3);
  test_support::drawPerson(image, 100, 30, 120, 287.0, 285.0);
  cv::Mat centi;
  image.convertTo(centi, CV_16U, 4.0);  // centi-kelvin counts
  ASSERT_TRUE(cv::imwrite(path("centi.png"), centi));
  std::ofstream(path("tlinear.yaml")) << "kelvin_per_count: 0.01\nkelvin_offset: 20\n";
  EXPECT_EQ(lineCount(run("--image " + path("centi.png") + " --mask-out " + path("m.png") + " --config " +
                          path("tlinear.yaml")).out), 1);
  // The command line wins over the file.
  EXPECT_EQ(run("--image " + path("centi.png") + " --mask-out " + path("m.png") + " --config " + path("tlinear.yaml") +
                " --kelvin-offset 0").out, "no person found\n");
  // A cloud read with a range limit from the file.
  const auto scan = scanWithTwoPeople();
  pcl::PointCloud<pcl::PointXYZ> xyz;
  for (const auto& p : scan.points) xyz.push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
  ASSERT_EQ(pcl::io::savePCDFileBinary(path("scan.pcd"), xyz), 0);
  std::ofstream(path("near.yaml")) << "lidar_max_range_m: 9\n";
  EXPECT_EQ(lineCount(run("--cloud " + path("scan.pcd") + " --clusters-out " + path("o.pcd") + " --config " +
                          path("near.yaml")).out), 1);
}

TEST_F(DetectPeopleCli, RegionsCutByTheImageBorderAreNotReportedButCounted) {
  cv::Mat image = twoPeople16();
  test_support::drawPerson(image, 315, 60, 120, 307.0, 301.0);  // its right half beyond the edge
  ASSERT_TRUE(cv::imwrite(path("cut.png"), image));
  const RunResult r = run("--image " + path("cut.png") + " --mask-out " + path("m.png") + " --explain");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(lineCount(r.out), 3) << r.out;
  EXPECT_NE(r.out.find("\ncut by the image border: 1 (not reported)\n"), std::string::npos) << r.out;
  EXPECT_NE(r.err.find("not a person (cut_by_border)"), std::string::npos) << r.err;
  EXPECT_EQ(cv::countNonZero(cv::imread(path("m.png"), cv::IMREAD_UNCHANGED) > 2), 0);
}

TEST_F(DetectPeopleCli, NobodyFoundIsExitZero) {
  ASSERT_TRUE(cv::imwrite(path("empty.png"), test_support::thermalBackground(cv::Size(160, 120), 290.0, 0.2, 4)));
  const RunResult r = run("--image " + path("empty.png") + " --mask-out " + path("m.png"));
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.out, "no person found\n");
  EXPECT_EQ(cv::countNonZero(cv::imread(path("m.png"), cv::IMREAD_UNCHANGED)), 0);
}

TEST_F(DetectPeopleCli, PcdAndKittiCloudsGiveLabelledClustersAndOneLinePerPerson) {
  const auto scan = scanWithTwoPeople();
  // PCD with intensity, PCD with x y z only, KITTI .bin: the same people.
  pcl::PointCloud<pcl::PointXYZI> with_i;
  pcl::PointCloud<pcl::PointXYZ> xyz;
  std::ofstream bin(path("scan.bin"), std::ios::binary);
  for (const auto& p : scan.points) {
    pcl::PointXYZI q;
    q.x = p.x();
    q.y = p.y();
    q.z = p.z();
    q.intensity = 7.f;
    with_i.push_back(q);
    xyz.push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
    const float v[4] = {p.x(), p.y(), p.z(), 0.3f};
    bin.write(reinterpret_cast<const char*>(v), sizeof v);
  }
  bin.close();
  ASSERT_EQ(pcl::io::savePCDFileBinary(path("scan_i.pcd"), with_i), 0);
  ASSERT_EQ(pcl::io::savePCDFileASCII(path("scan.pcd"), xyz), 0);
  std::string first;
  for (const char* name : {"scan_i.pcd", "scan.pcd", "scan.bin"}) {
    const RunResult r = run(std::string("--cloud ") + path(name) + " --clusters-out " + path("people.pcd"));
    ASSERT_EQ(r.exit_code, 0) << name << ": " << r.err;
    ASSERT_EQ(lineCount(r.out), 2) << name << ": " << r.out;
    if (first.empty()) first = r.out;
    EXPECT_EQ(r.out, first) << name;
  }
  std::smatch m;
  ASSERT_TRUE(std::regex_search(first, m, kCloudLine)) << first;
  EXPECT_EQ(m[1], "1");
  EXPECT_NEAR(std::stod(m[2]), 7.0, 0.3);  // the nearer person first
  EXPECT_NEAR(std::stod(m[3]), 1.0, 0.2);
  const int points_1 = std::stoi(m[8]);
  // The written clusters: x y z label, the printed counts per label.
  pcl::PCLPointCloud2 blob;
  ASSERT_EQ(pcl::io::loadPCDFile(path("people.pcd"), blob), 0);
  std::vector<std::string> fields;
  for (const auto& f : blob.fields) fields.push_back(f.name);
  EXPECT_EQ(fields, (std::vector<std::string>{"x", "y", "z", "label"}));
  pcl::PointCloud<pcl::PointXYZL> people;
  pcl::fromPCLPointCloud2(blob, people);
  int label_1 = 0, other = 0;
  for (const auto& p : people) (p.label == 1 ? label_1 : other) += 1;
  EXPECT_EQ(label_1, points_1);
  EXPECT_GT(other, 0);
}

TEST_F(DetectPeopleCli, CloudWithNobodyWritesAnEmptyClusterFile) {
  pcl::PointCloud<pcl::PointXYZ> ground;
  for (int i = 0; i < 2000; ++i) ground.push_back(pcl::PointXYZ(2.0f + 0.01f * i, 0.002f * i, -1.8f));
  ASSERT_EQ(pcl::io::savePCDFileBinary(path("ground.pcd"), ground), 0);
  const RunResult r = run("--cloud " + path("ground.pcd") + " --clusters-out " + path("none.pcd") + " --view-out " +
                          path("top.png") + " --explain");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "no person found\n");
  pcl::PCLPointCloud2 blob;
  ASSERT_EQ(pcl::io::loadPCDFile(path("none.pcd"), blob), 0);
  EXPECT_EQ(blob.width * blob.height, 0u);
  EXPECT_FALSE(cv::imread(path("top.png")).empty());
  EXPECT_NE(r.err.find("ground: tilt"), std::string::npos);
}

// Bad input: exit 1, nothing on stdout, exactly one line on stderr naming the problem.
TEST_F(DetectPeopleCli, BadInputIsOneLineAndExitOne) {
  std::ofstream(path("notes.png")) << "not an image";
  std::ofstream(path("odd.bin"), std::ios::binary) << "12345";
  std::ofstream(path("scan.xyz")) << "1 2 3\n";
  std::ofstream(path("broken.pcd")) << "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
                                       "WIDTH 5\nHEIGHT 1\nPOINTS 5\nDATA binary\nabc";  // truncated
  pcl::PointCloud<pcl::PointXY> flat;
  flat.push_back(pcl::PointXY{1.f, 2.f});
  ASSERT_EQ(pcl::io::savePCDFileASCII(path("xy.pcd"), flat), 0);
  cv::Mat colour(32, 32, CV_8UC3, cv::Scalar(10, 200, 30));
  ASSERT_TRUE(cv::imwrite(path("colour.png"), colour));
  ASSERT_TRUE(cv::imwrite(path("float.tiff"), cv::Mat(8, 8, CV_32FC1, cv::Scalar(1.5))));
  ASSERT_TRUE(cv::imwrite(path("ok.png"), test_support::thermalBackground(cv::Size(64, 48), 290.0)));
  std::ofstream(path("bad.yaml")) << "lidar_min_points: 0\n";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--image " + path("missing.png") + " --mask-out " + path("m.png"), "no such file"},
      {"--image " + path("notes.png") + " --mask-out " + path("m.png"), "not a readable PNG, TIFF or JPEG"},
      {"--image " + path("colour.png") + " --mask-out " + path("m.png"), "a colour image"},
      {"--image " + path("float.tiff") + " --mask-out " + path("m.png"), "neither 8- nor 16-bit"},
      {"--image " + path("ok.png") + " --mask-out " + path("m.jpg"), "write the mask as .png"},
      {"--image " + path("ok.png") + " --mask-out " + path("no_dir/m.png"), "cannot write"},
      {"--image " + path("ok.png") + " --mask-out " + path("m.png") + " --kelvin-per-count -1",
       "parameter 'kelvin_per_count' = -1: must be in [0, 10]"},
      {"--cloud " + path("missing.pcd") + " --clusters-out " + path("o.pcd"), "no such file"},
      {"--cloud " + path("odd.bin") + " --clusters-out " + path("o.pcd"), "not a whole number of KITTI points"},
      {"--cloud " + path("scan.xyz") + " --clusters-out " + path("o.pcd"), "unknown format '.xyz'"},
      {"--cloud " + path("broken.pcd") + " --clusters-out " + path("o.pcd"), "not a readable PCD file"},
      {"--cloud " + path("xy.pcd") + " --clusters-out " + path("o.pcd"), "no 'z' field"},
      {"--cloud " + dir_ + " --clusters-out " + path("o.pcd"), "not a regular file"},
      {"--image " + path("ok.png") + " --mask-out " + path("m.png") + " --config " + path("missing.yaml"), "missing.yaml"},
      {"--image " + path("ok.png") + " --mask-out " + path("m.png") + " --config " + path("bad.yaml"),
       "parameter 'lidar_min_points' = 0: must be an integer in [1, 1000000]"},
  };
  for (const auto& [args, reason] : cases) {
    const RunResult r = run(args);
    EXPECT_EQ(r.exit_code, 1) << args << "\n" << r.err;
    EXPECT_EQ(r.out, "") << args;
    EXPECT_EQ(lineCount(r.err), 1) << args << "\n" << r.err;
    EXPECT_EQ(r.err.rfind("detect_people: ", 0), 0u) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(reason), std::string::npos) << args << "\n" << r.err;
  }
}

TEST_F(DetectPeopleCli, BadCommandLineIsUsageAndExitTwo) {
  for (const std::string args : {"", "--image a.png", "--cloud a.pcd", "--image a.png --cloud b.pcd --mask-out m.png",
                                 "--image a.png --mask-out m.png --bogus 1", "--image a.png --mask-out m.png --kelvin-offset x",
                                 "--image a.png --mask-out m.png --flip sideways", "--cloud a.pcd --clusters-out o.pcd --flip both"}) {
    const RunResult r = run(args);
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_NE(r.err.find("usage: detect_people"), std::string::npos) << args;
  }
  const RunResult help = run("--help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.out.find("--clusters-out"), std::string::npos);
}

}  // namespace
}  // namespace thermal_lidar_calibration
