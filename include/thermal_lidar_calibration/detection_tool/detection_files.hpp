#pragma once
// The files detect_people reads and writes. ROS-free (OpenCV imgcodecs, PCL io). Every reader
// throws std::invalid_argument with one line naming the file and what is wrong with it.

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace thermal_lidar_calibration {
namespace detection_tool {

// An 8- or 16-bit PNG, TIFF or JPEG as CV_8UC1 / CV_16UC1. A 3- or 4-channel image whose colour
// channels are equal (grey stored as colour, as many thermal exports are) is read as grey; a
// real colour image, a float image, or a file that is missing or not an image is refused.
cv::Mat readThermalImage(const std::string& path);

struct CloudFile {
  std::vector<Eigen::Vector3f> points;  // m, as stored
  std::vector<float> intensity;         // empty if the file has none
};

// A PCD with float x, y, z (and optionally intensity) or a KITTI .bin (float32 x, y, z,
// reflectance per point); chosen by the extension (.pcd / .bin).
CloudFile readCloud(const std::string& path);

// A binary PCD with float x, y, z and uint32 label (PCL's PointXYZL layout).
void writeLabelledCloud(const std::string& path, const std::vector<Eigen::Vector3f>& points,
                        const std::vector<std::uint32_t>& labels);

// An 8-bit single-channel PNG; throws if it cannot be written.
void writeMask(const std::string& path, const cv::Mat& mask);
// Any image OpenCV can write (by extension); throws if it cannot be written.
void writeImage(const std::string& path, const cv::Mat& image);

}  // namespace detection_tool
}  // namespace thermal_lidar_calibration
