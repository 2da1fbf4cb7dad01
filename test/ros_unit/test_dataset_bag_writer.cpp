// DatasetBagWriter: every pair whose write() returned is in the bag, also when the disk fills
// (simulated with RLIMIT_FSIZE: a write past the limit fails with EFBIG, as ENOSPC would).

#include "thermal_lidar_calibration/ros/dataset_bag.hpp"
#include "thermal_lidar_calibration/ros/msg_conversion.hpp"

#include "../support/test_files.hpp"

#include <gtest/gtest.h>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <cstdio>
#include <functional>
#include <random>
#include <string>

namespace tlc = thermal_lidar_calibration;
using tlc::ros_io::DatasetBagWriter;

namespace {

struct PairMessages {
  sensor_msgs::Image image, mask;
  sensor_msgs::PointCloud2 clusters;
  sensor_msgs::CameraInfo info;
};

// A 640x512 mono16 image of noise (compresses poorly, like a real thermal frame), a mask with
// one person and a cluster of 200 points, stamped `stamp_s`.
PairMessages makePair(double stamp_s, unsigned seed) {
  std::mt19937 rng(seed);
  cv::Mat image(512, 640, CV_16UC1);
  for (int r = 0; r < image.rows; ++r) {
    for (int c = 0; c < image.cols; ++c) image.at<std::uint16_t>(r, c) = 7000 + rng() % 500;
  }
  cv::Mat mask = cv::Mat::zeros(512, 640, CV_8UC1);
  mask(cv::Rect(300, 200, 40, 120)).setTo(1);
  std::vector<Eigen::Vector3f> points;
  std::vector<std::int32_t> labels;
  for (int i = 0; i < 200; ++i) {
    points.emplace_back(8.0f, 0.001f * i, 0.01f * i);
    labels.push_back(1);
  }
  tlc::CameraModel camera;
  camera.width = 640;
  camera.height = 512;
  camera.fx = camera.fy = 770.0;
  camera.cx = 320.0;
  camera.cy = 256.0;
  PairMessages m;
  m.image = tlc::ros_io::encodeMonoImage(image, "thermal_optical", stamp_s);
  m.mask = tlc::ros_io::encodeMonoImage(mask, "thermal_optical", stamp_s);
  m.clusters = tlc::ros_io::encodeClusters(points, labels, "velodyne", stamp_s);
  m.info = tlc::ros_io::cameraInfoFromModel(camera);
  return m;
}

void write(DatasetBagWriter& writer, const PairMessages& m) {
  writer.write(m.image, m.mask, m.clusters, m.info);
}

// Runs `body` in a child process whose files may not grow past `limit_bytes`; SIGXFSZ is ignored
// so that the write fails with EFBIG instead of killing it. Returns the child's wait status.
int runWithFileSizeLimit(rlim_t limit_bytes, const std::function<int()>& body) {
  std::fflush(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) {
    std::signal(SIGXFSZ, SIG_IGN);
    const rlimit limit{limit_bytes, limit_bytes};
    ::setrlimit(RLIMIT_FSIZE, &limit);
    std::_Exit(body());
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  return status;
}

}  // namespace

// A disk that fills during an append: write() throws (the node then stops recording) instead of
// ending the process (rosbag::Bag's destructor used to throw again: std::terminate), and the bag
// still holds every pair written before.
TEST(DatasetBagWriter, FullDiskIsAnErrorAndEarlierPairsSurvive) {
  const std::string dir = tlc::test_support::tempDir("tlc_dataset_full_");
  const std::string path = dir + "/dataset.bag";
  constexpr int kAttempts = 12;
  const int status = runWithFileSizeLimit(3u << 20, [&] {
    int written = 0;
    try {
      DatasetBagWriter writer(path, false);
      for (; written < kAttempts; ++written) write(writer, makePair(100.0 + written, written));
    } catch (const std::runtime_error& e) {
      std::fprintf(stderr, "write %d failed as expected: %s\n", written + 1, e.what());
      return written;
    }
    return 100;  // the limit was never reached: the test is wrong
  });
  ASSERT_TRUE(WIFEXITED(status)) << "the writer ended the process (signal "
                                 << (WIFSIGNALED(status) ? WTERMSIG(status) : 0) << ")";
  const int written = WEXITSTATUS(status);
  ASSERT_LT(written, kAttempts) << "the file size limit was never reached";
  ASSERT_GE(written, 1);
  const auto contents = tlc::ros_io::readDatasetBag(path);
  EXPECT_EQ(static_cast<int>(contents.frames.size()), written);
  EXPECT_TRUE(contents.errors.empty());
  std::filesystem::remove_all(dir);
}
