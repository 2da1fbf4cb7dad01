#pragma once
// Small bags for the calibrate_bag CLI tests, written with the rosbag C++ API: people as
// cylinders of LiDAR points, masks made by projecting those points with a known extrinsic, so
// the truth has zero loss. Options let a test break one thing at a time.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <rosbag/bag.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace tlc_cli_test {

struct BagSpec {
  int frames = 40;
  int width = 160, height = 128;
  double fx = 150.0, fy = 150.0, cx = 80.0, cy = 64.0;
  int camera_info_width = 0;      // 0 = width (set to something else for a size mismatch)
  bool write_camera_info = true;
  std::string mask_encoding = "mono8";
  bool label_field = true;
  bool people_in_mask = true;     // false: masks are empty (zero pairs kept)
  int nonfinite_every = 0;        // every n-th point of every cloud is NaN/inf (0 = none)
  std::string camera_frame = "thermal_optical";
  std::string lidar_frame = "velodyne";
};

// p_C = R p_L + t: LiDAR x forward, y left, z up -> camera x right, y down, z forward, with a
// small extra rotation.
inline Eigen::Matrix3d truthRotation() {
  Eigen::Matrix3d base;
  base << 0, -1, 0, 0, 0, -1, 1, 0, 0;
  const Eigen::Matrix3d tweak =
      (Eigen::AngleAxisd(0.03, Eigen::Vector3d::UnitX()) *
       Eigen::AngleAxisd(-0.05, Eigen::Vector3d::UnitY()) *
       Eigen::AngleAxisd(0.02, Eigen::Vector3d::UnitZ()))
          .toRotationMatrix();
  return tweak * base;
}
inline Eigen::Vector3d truthTranslation() { return Eigen::Vector3d(0.05, -0.10, 0.08); }

inline void writeTruthFile(const std::string& path) {
  const Eigen::AngleAxisd aa(truthRotation());
  const Eigen::Vector3d r = aa.angle() * aa.axis();
  const Eigen::Vector3d t = truthTranslation();
  std::ofstream out(path);
  out.precision(17);
  out << "rotation_vector: [" << r.x() << ", " << r.y() << ", " << r.z() << "]\n";
  out << "translation: [" << t.x() << ", " << t.y() << ", " << t.z() << "]\n";
}

inline sensor_msgs::CameraInfo cameraInfo(const BagSpec& s, const ros::Time& stamp) {
  sensor_msgs::CameraInfo info;
  info.header.stamp = stamp;
  info.header.frame_id = s.camera_frame;
  info.width = s.camera_info_width ? s.camera_info_width : s.width;
  info.height = s.height;
  info.distortion_model = "plumb_bob";
  info.D = {0, 0, 0, 0, 0};
  info.K = {s.fx, 0, s.cx, 0, s.fy, s.cy, 0, 0, 1};
  info.R = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  info.P = {s.fx, 0, s.cx, 0, 0, s.fy, s.cy, 0, 0, 0, 1, 0};
  return info;
}

inline void writeCameraInfoYaml(const BagSpec& s, const std::string& path) {
  std::ofstream out(path);
  out << "image_width: " << s.width << "\nimage_height: " << s.height << "\n"
      << "camera_name: test\ncamera_matrix: {rows: 3, cols: 3, data: [" << s.fx << ", 0, " << s.cx
      << ", 0, " << s.fy << ", " << s.cy << ", 0, 0, 1]}\n"
      << "distortion_model: plumb_bob\n"
      << "distortion_coefficients: {rows: 1, cols: 5, data: [0, 0, 0, 0, 0]}\n";
}

inline sensor_msgs::PointCloud2 cloudMsg(const std::vector<Eigen::Vector3f>& points,
                                         const std::vector<int>& labels, bool label_field) {
  sensor_msgs::PointCloud2 msg;
  const char* names[4] = {"x", "y", "z", label_field ? "label" : "intensity"};
  for (int k = 0; k < 4; ++k) {
    sensor_msgs::PointField f;
    f.name = names[k];
    f.offset = 4 * k;
    f.datatype = (k == 3 && label_field) ? sensor_msgs::PointField::INT32
                                         : sensor_msgs::PointField::FLOAT32;
    f.count = 1;
    msg.fields.push_back(f);
  }
  msg.height = 1;
  msg.width = points.size();
  msg.point_step = 16;
  msg.row_step = 16 * msg.width;
  msg.is_dense = false;
  msg.data.resize(msg.row_step);
  for (std::size_t i = 0; i < points.size(); ++i) {
    std::uint8_t* p = msg.data.data() + 16 * i;
    std::memcpy(p, points[i].data(), 12);
    if (label_field) {
      const std::int32_t l = labels[i];
      std::memcpy(p + 12, &l, 4);
    } else {
      const float v = static_cast<float>(labels[i]);
      std::memcpy(p + 12, &v, 4);
    }
  }
  return msg;
}

inline sensor_msgs::Image imageMsg(const std::vector<std::uint8_t>& pixels, int width, int height,
                                   const std::string& encoding) {
  sensor_msgs::Image msg;
  msg.width = width;
  msg.height = height;
  msg.encoding = encoding;
  const int channels = encoding == "rgb8" ? 3 : 1;
  msg.step = width * channels;
  msg.data.resize(static_cast<std::size_t>(msg.step) * height);
  for (int i = 0; i < width * height; ++i) {
    for (int c = 0; c < channels; ++c) msg.data[i * channels + c] = pixels[i];
  }
  return msg;
}

// Writes the bag; returns the number of frames written.
inline void writeBag(const std::string& path, const BagSpec& s) {
  rosbag::Bag bag(path, rosbag::bagmode::Write);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  const Eigen::Matrix3d R = truthRotation();
  const Eigen::Vector3d t = truthTranslation();
  const double nan = std::numeric_limits<float>::quiet_NaN();
  const double inf = std::numeric_limits<float>::infinity();
  for (int f = 0; f < s.frames; ++f) {
    const ros::Time stamp(1000.0 + 0.1 * f);
    const int people = 1 + (f % 2);
    std::vector<Eigen::Vector3f> points;
    std::vector<int> labels;
    std::vector<std::uint8_t> mask(static_cast<std::size_t>(s.width) * s.height, 0);
    for (int h = 0; h < people; ++h) {
      // Person h stands in its own lateral sector so the two never overlap; 2.5-6 m away.
      const double x = 2.5 + 3.5 * u01(rng);
      const double half_width = 0.45 * x * s.cx / s.fx;
      const double y = people == 1 ? half_width * (2.0 * u01(rng) - 1.0)
                                   : (h == 0 ? -half_width : 0.15 * half_width) +
                                         0.85 * half_width * u01(rng);
      // The thermal silhouette: a dense sampling of the half cylinder facing the sensors.
      // The LiDAR sees a sparse subset of the same surface.
      for (int k = 0; k < 12000; ++k) {
        const bool lidar_point = k % 80 == 0;
        const double a = M_PI * (0.5 + u01(rng));
        const double z = -1.0 + 1.7 * u01(rng);
        const Eigen::Vector3d p(x + 0.25 * std::cos(a), y + 0.25 * std::sin(a), z);
        const Eigen::Vector3d pc = R * p + t;
        const int uu = static_cast<int>(std::lround(s.fx * pc.x() / pc.z() + s.cx));
        const int vv = static_cast<int>(std::lround(s.fy * pc.y() / pc.z() + s.cy));
        if (uu < 0 || vv < 0 || uu >= s.width || vv >= s.height) continue;
        if (lidar_point) {
          points.emplace_back(p.cast<float>());
          labels.push_back(h + 1);
        }
        if (s.people_in_mask) {
          mask[static_cast<std::size_t>(vv) * s.width + uu] = static_cast<std::uint8_t>(h + 1);
        }
      }
    }
    if (s.nonfinite_every > 0) {
      for (std::size_t i = 0; i < points.size(); i += s.nonfinite_every) {
        points[i].x() = static_cast<float>(i % 2 ? nan : inf);
      }
    }
    std::vector<std::uint8_t> image(mask.size());
    for (std::size_t i = 0; i < mask.size(); ++i) image[i] = mask[i] ? 200 : 30;

    sensor_msgs::Image image_msg = imageMsg(image, s.width, s.height, "mono8");
    sensor_msgs::Image mask_msg = imageMsg(mask, s.width, s.height, s.mask_encoding);
    sensor_msgs::PointCloud2 cloud = cloudMsg(points, labels, s.label_field);
    image_msg.header.stamp = mask_msg.header.stamp = stamp;
    image_msg.header.frame_id = mask_msg.header.frame_id = s.camera_frame;
    cloud.header.stamp = stamp + ros::Duration(0.01);
    cloud.header.frame_id = s.lidar_frame;
    if (s.write_camera_info) bag.write("/thermal/camera_info", stamp, cameraInfo(s, stamp));
    bag.write("/thermal/image_raw", stamp, image_msg);
    bag.write("/thermal/human_mask", stamp + ros::Duration(0.001), mask_msg);
    bag.write("/lidar/human_clusters", stamp + ros::Duration(0.002), cloud);
  }
  bag.close();
}

}  // namespace tlc_cli_test
