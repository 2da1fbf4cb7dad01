#pragma once
// One kept pair as the node records it (image, mask, clusters, camera_info), for the dataset bag
// writer's tests and benchmark: a 640x512 mono16 image of noise (compresses poorly, like a real
// thermal frame), a mask with one person and a cluster of 200 points.

#include "thermal_lidar_calibration/ros/msg_conversion.hpp"

#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>

#include <opencv2/core.hpp>

#include <cstdint>
#include <random>
#include <vector>

namespace thermal_lidar_calibration {
namespace test_support {

struct PairMessages {
  sensor_msgs::Image image, mask;
  sensor_msgs::PointCloud2 clusters;
  sensor_msgs::CameraInfo info;
};

inline PairMessages makePairMessages(double stamp_s, unsigned seed) {
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
  CameraModel camera;
  camera.width = 640;
  camera.height = 512;
  camera.fx = camera.fy = 770.0;
  camera.cx = 320.0;
  camera.cy = 256.0;
  PairMessages m;
  m.image = ros_io::encodeMonoImage(image, "thermal_optical", stamp_s);
  m.mask = ros_io::encodeMonoImage(mask, "thermal_optical", stamp_s);
  m.clusters = ros_io::encodeClusters(points, labels, "velodyne", stamp_s);
  m.info = ros_io::cameraInfoFromModel(camera);
  return m;
}

}  // namespace test_support
}  // namespace thermal_lidar_calibration
