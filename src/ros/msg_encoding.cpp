// Encoders: core types -> ROS messages (the generator and dataset bags). The decoders live in
// msg_conversion.cpp.

#include "thermal_lidar_calibration/ros/msg_conversion.hpp"

#include <sensor_msgs/image_encodings.h>

#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

namespace thermal_lidar_calibration {
namespace ros_io {
namespace {

sensor_msgs::PointField field(const std::string& name, std::uint32_t offset, std::uint8_t datatype) {
  sensor_msgs::PointField f;
  f.name = name;
  f.offset = offset;
  f.datatype = datatype;
  f.count = 1;
  return f;
}

void fillCloudHeader(sensor_msgs::PointCloud2& cloud, std::size_t n, std::uint32_t point_step,
                     const std::string& frame_id, double stamp_s) {
  cloud.header.frame_id = frame_id;
  cloud.header.stamp = ros::Time(stamp_s);
  cloud.height = 1;
  cloud.width = static_cast<std::uint32_t>(n);
  cloud.is_bigendian = false;
  cloud.point_step = point_step;
  cloud.row_step = point_step * cloud.width;
  cloud.data.resize(static_cast<std::size_t>(cloud.row_step));
}

bool finite(const Eigen::Vector3f& p) { return std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z()); }

// x, y, z (FLOAT32 at 0, 4, 8) and one 4-byte field `name` at 12: point_step 16. The caller has
// checked that `extra` has one value per point.
template <typename T>
sensor_msgs::PointCloud2 encodeXyzPlusField(const std::vector<Eigen::Vector3f>& points,
                                            const std::vector<T>& extra, const std::string& name,
                                            std::uint8_t datatype, const std::string& frame_id,
                                            double stamp_s) {
  static_assert(sizeof(T) == 4, "the extra field is 4 bytes at offset 12");
  sensor_msgs::PointCloud2 cloud;
  cloud.fields = {field("x", 0, sensor_msgs::PointField::FLOAT32), field("y", 4, sensor_msgs::PointField::FLOAT32),
                  field("z", 8, sensor_msgs::PointField::FLOAT32), field(name, 12, datatype)};
  fillCloudHeader(cloud, points.size(), 16, frame_id, stamp_s);
  cloud.is_dense = true;
  for (std::size_t i = 0; i < points.size(); ++i) {
    std::uint8_t* p = &cloud.data[i * 16];
    std::memcpy(p, points[i].data(), 12);
    std::memcpy(p + 12, &extra[i], 4);
    if (!finite(points[i])) cloud.is_dense = false;
  }
  return cloud;
}

}  // namespace

sensor_msgs::Image encodeMonoImage(const cv::Mat& mat, const std::string& frame_id, double stamp_s) {
  if (mat.empty()) throw std::invalid_argument("encodeMonoImage: empty image");
  if (mat.type() != CV_8UC1 && mat.type() != CV_16UC1) {
    throw std::invalid_argument("encodeMonoImage: only CV_8UC1 (mono8) and CV_16UC1 (mono16) can be encoded");
  }
  sensor_msgs::Image msg;
  msg.header.frame_id = frame_id;
  msg.header.stamp = ros::Time(stamp_s);
  msg.height = static_cast<std::uint32_t>(mat.rows);
  msg.width = static_cast<std::uint32_t>(mat.cols);
  msg.encoding = mat.type() == CV_8UC1 ? sensor_msgs::image_encodings::MONO8 : sensor_msgs::image_encodings::MONO16;
  msg.is_bigendian = false;  // host order; every supported platform is little-endian
  const std::size_t row_bytes = static_cast<std::size_t>(mat.cols) * mat.elemSize();
  msg.step = static_cast<std::uint32_t>(row_bytes);
  msg.data.resize(row_bytes * mat.rows);
  for (int r = 0; r < mat.rows; ++r) std::memcpy(&msg.data[r * row_bytes], mat.ptr(r), row_bytes);
  return msg;
}

sensor_msgs::PointCloud2 encodeClusters(const std::vector<Eigen::Vector3f>& points,
                                        const std::vector<std::int32_t>& labels, const std::string& frame_id,
                                        double stamp_s) {
  if (points.size() != labels.size()) {
    throw std::invalid_argument("encodeClusters: " + std::to_string(points.size()) + " points but " +
                                std::to_string(labels.size()) + " labels");
  }
  return encodeXyzPlusField(points, labels, "label", sensor_msgs::PointField::INT32, frame_id, stamp_s);
}

sensor_msgs::PointCloud2 encodePointsWithIntensity(const std::vector<Eigen::Vector3f>& points,
                                                   const std::vector<float>& intensity, const std::string& frame_id,
                                                   double stamp_s) {
  if (points.size() != intensity.size()) {
    throw std::invalid_argument("encodePointsWithIntensity: " + std::to_string(points.size()) + " points but " +
                                std::to_string(intensity.size()) + " intensities");
  }
  return encodeXyzPlusField(points, intensity, "intensity", sensor_msgs::PointField::FLOAT32, frame_id,
                            stamp_s);
}

sensor_msgs::CameraInfo cameraInfoFromModel(const CameraModel& camera) {
  sensor_msgs::CameraInfo info;
  info.width = static_cast<std::uint32_t>(camera.width);
  info.height = static_cast<std::uint32_t>(camera.height);
  info.distortion_model = "plumb_bob";
  info.D.assign(camera.distortion.begin(), camera.distortion.end());
  info.K = {camera.fx, camera.skew, camera.cx, 0.0, camera.fy, camera.cy, 0.0, 0.0, 1.0};
  info.R = {1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
  info.P = {camera.fx, camera.skew, camera.cx, 0.0, 0.0, camera.fy, camera.cy, 0.0, 0.0, 0.0, 1.0, 0.0};
  return info;
}

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
