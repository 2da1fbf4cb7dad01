#include "thermal_lidar_calibration/detection_tool/detection_files.hpp"

#include <opencv2/imgcodecs.hpp>
#include <pcl/PCLPointCloud2.h>
#include <pcl/console/print.h>
#include <pcl/conversions.h>
#include <pcl/io/pcd_io.h>
#include <pcl/point_types.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <stdexcept>
#include <sys/stat.h>

namespace thermal_lidar_calibration {
namespace detection_tool {
namespace {

std::string lowerExtension(const std::string& path) {
  const auto dot = path.find_last_of('.');
  const auto slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

void requireReadableFile(const std::string& path, const std::string& what) {
  struct stat info {};
  if (stat(path.c_str(), &info) != 0) throw std::invalid_argument(what + " " + path + ": no such file");
  if (!S_ISREG(info.st_mode)) throw std::invalid_argument(what + " " + path + ": not a regular file");
  std::ifstream probe(path, std::ios::binary);
  if (!probe) throw std::invalid_argument(what + " " + path + ": cannot be opened (permissions?)");
}

bool hasField(const pcl::PCLPointCloud2& cloud, const std::string& name) {
  return std::any_of(cloud.fields.begin(), cloud.fields.end(), [&](const pcl::PCLPointField& f) { return f.name == name; });
}

CloudFile readPcd(const std::string& path) {
  pcl::PCLPointCloud2 blob;
  pcl::PCDReader reader;
  // PCL would print its own complaint to stderr as well; ours is the one line the user gets.
  const pcl::console::VERBOSITY_LEVEL verbosity = pcl::console::getVerbosityLevel();
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  const int status = reader.read(path, blob);
  pcl::console::setVerbosityLevel(verbosity);
  if (status < 0) {
    throw std::invalid_argument("cloud " + path + ": not a readable PCD file");
  }
  for (const char* axis : {"x", "y", "z"}) {
    if (!hasField(blob, axis)) throw std::invalid_argument("cloud " + path + ": no '" + axis + "' field (need x, y, z)");
  }
  CloudFile out;
  if (hasField(blob, "intensity")) {
    pcl::PointCloud<pcl::PointXYZI> cloud;
    pcl::fromPCLPointCloud2(blob, cloud);
    for (const auto& p : cloud) {
      out.points.emplace_back(p.x, p.y, p.z);
      out.intensity.push_back(p.intensity);
    }
  } else {
    pcl::PointCloud<pcl::PointXYZ> cloud;
    pcl::fromPCLPointCloud2(blob, cloud);
    for (const auto& p : cloud) out.points.emplace_back(p.x, p.y, p.z);
  }
  return out;
}

CloudFile readKittiBin(const std::string& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  const std::streamsize bytes = in.tellg();
  if (bytes % 16 != 0) {
    throw std::invalid_argument("cloud " + path + ": " + std::to_string(bytes) +
                                " bytes is not a whole number of KITTI points (16 bytes: float32 x, y, z, reflectance)");
  }
  std::vector<float> values(static_cast<std::size_t>(bytes / 4));
  in.seekg(0);
  if (!in.read(reinterpret_cast<char*>(values.data()), bytes)) throw std::invalid_argument("cloud " + path + ": read failed");
  CloudFile out;
  out.points.reserve(values.size() / 4);
  out.intensity.reserve(values.size() / 4);
  for (std::size_t i = 0; i + 3 < values.size(); i += 4) {
    out.points.emplace_back(values[i], values[i + 1], values[i + 2]);
    out.intensity.push_back(values[i + 3]);
  }
  return out;
}

}  // namespace

cv::Mat readThermalImage(const std::string& path) {
  requireReadableFile(path, "image");
  cv::Mat image;
  try {
    image = cv::imread(path, cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception&) {
    image.release();
  }
  if (image.empty()) {
    throw std::invalid_argument("image " + path + ": not a readable PNG, TIFF or JPEG image");
  }
  const int depth = image.depth();
  if (depth != CV_8U && depth != CV_16U) {
    throw std::invalid_argument("image " + path + ": pixels are neither 8- nor 16-bit unsigned integers "
                                "(floating-point or signed images are not thermal counts)");
  }
  const int channels = image.channels();
  if (channels == 1) return image;
  if (channels != 3 && channels != 4) {
    throw std::invalid_argument("image " + path + ": " + std::to_string(channels) + " channels (need 1, or 3 equal ones)");
  }
  std::vector<cv::Mat> planes;
  cv::split(image, planes);
  if (cv::countNonZero(planes[0] != planes[1]) > 0 || cv::countNonZero(planes[0] != planes[2]) > 0) {
    throw std::invalid_argument("image " + path + ": a colour image (its channels differ); "
                                "give the raw single-channel thermal image, not a colour-mapped rendering");
  }
  return planes[0];
}

CloudFile readCloud(const std::string& path) {
  requireReadableFile(path, "cloud");
  const std::string ext = lowerExtension(path);
  CloudFile cloud;
  if (ext == "pcd") {
    cloud = readPcd(path);
  } else if (ext == "bin") {
    cloud = readKittiBin(path);
  } else {
    throw std::invalid_argument("cloud " + path + ": unknown format '." + ext + "' (need .pcd or KITTI .bin)");
  }
  if (cloud.points.empty()) throw std::invalid_argument("cloud " + path + ": holds no points");
  return cloud;
}

void writeLabelledCloud(const std::string& path, const std::vector<Eigen::Vector3f>& points,
                        const std::vector<std::uint32_t>& labels) {
  pcl::PointCloud<pcl::PointXYZL> cloud;
  cloud.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    pcl::PointXYZL p;
    p.x = points[i].x();
    p.y = points[i].y();
    p.z = points[i].z();
    p.label = labels[i];
    cloud.push_back(p);
  }
  cloud.width = static_cast<std::uint32_t>(cloud.size());
  cloud.height = 1;
  // PCL refuses to write an empty cloud; a header-only PCD says "nobody" just as well.
  if (cloud.empty()) {
    std::ofstream out(path);
    out << "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS x y z label\nSIZE 4 4 4 4\n"
           "TYPE F F F U\nCOUNT 1 1 1 1\nWIDTH 0\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 0\nDATA ascii\n";
    if (!out) throw std::invalid_argument("cannot write " + path);
    return;
  }
  if (pcl::io::savePCDFileBinary(path, cloud) != 0) throw std::invalid_argument("cannot write " + path);
}

void writeImage(const std::string& path, const cv::Mat& image) {
  bool ok = false;
  try {
    ok = cv::imwrite(path, image);
  } catch (const cv::Exception&) {
    ok = false;
  }
  if (!ok) throw std::invalid_argument("cannot write " + path + " (folder missing, or no image extension?)");
}

void writeMask(const std::string& path, const cv::Mat& mask) {
  if (lowerExtension(path) != "png") throw std::invalid_argument("mask " + path + ": write the mask as .png (lossless)");
  writeImage(path, mask);
}

}  // namespace detection_tool
}  // namespace thermal_lidar_calibration
