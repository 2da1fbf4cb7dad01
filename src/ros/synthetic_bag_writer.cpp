#include "thermal_lidar_calibration/ros/synthetic_bag_writer.hpp"

#include "thermal_lidar_calibration/ros/calibrated_tf_publisher.hpp"
#include "thermal_lidar_calibration/ros/msg_conversion.hpp"

#include <boost/make_shared.hpp>
#include <sensor_msgs/point_cloud2_iterator.h>
#include <tf2_msgs/TFMessage.h>

#include <cstring>
#include <random>
#include <stdexcept>
#include <utility>

namespace thermal_lidar_calibration {
namespace ros_io {
namespace {

namespace syn = synthetic;

// The connection header `rosbag record` stores for a latched topic: `rosbag play` then
// republishes it latched, so a node that subscribes after the first instant still receives it.
template <typename Msg>
boost::shared_ptr<ros::M_string> latchedConnectionHeader() {
  auto header = boost::make_shared<ros::M_string>();
  (*header)["type"] = ros::message_traits::datatype<Msg>();
  (*header)["md5sum"] = ros::message_traits::md5sum<Msg>();
  (*header)["message_definition"] = ros::message_traits::definition<Msg>();
  (*header)["callerid"] = "/make_synthetic_bag";
  (*header)["latching"] = "1";
  return header;
}

// Appends a float32 field `name` after the fields `msg` has (point_step grows by 4).
void appendFloatField(sensor_msgs::PointCloud2& msg, const std::string& name) {
  sensor_msgs::PointField field;
  field.name = name;
  field.offset = msg.point_step;
  field.datatype = sensor_msgs::PointField::FLOAT32;
  field.count = 1;
  msg.fields.push_back(field);
  msg.point_step += 4;
}

// Per-point capture times as the velodyne driver writes them: float32 `time`, seconds from the
// header stamp, after the other fields. `msg` is one of our own dense, unpadded clouds.
sensor_msgs::PointCloud2 withPointTimes(const sensor_msgs::PointCloud2& msg, const std::vector<float>& time_s) {
  if (time_s.size() != static_cast<std::size_t>(msg.width) * msg.height) {
    throw std::invalid_argument("withPointTimes: one time per point");
  }
  sensor_msgs::PointCloud2 out = msg;
  appendFloatField(out, "time");
  out.row_step = out.point_step * out.width;
  out.data.assign(static_cast<std::size_t>(out.row_step) * out.height, 0);
  for (std::size_t i = 0; i < time_s.size(); ++i) {
    std::uint8_t* p = out.data.data() + i * out.point_step;
    std::memcpy(p, msg.data.data() + i * msg.point_step, msg.point_step);
    std::memcpy(p + msg.point_step, &time_s[i], 4);
  }
  return out;
}

// A raw scan as a Velodyne driver's pointcloud nodelet writes it (x, y, z, intensity, ring),
// plus uint32 truth_id: the person each point lies on (0 = none), for scoring detectors.
sensor_msgs::PointCloud2 encodeRawScan(const syn::SyntheticFrame& f, const std::string& frame_id,
                                       double stamp_s) {
  sensor_msgs::PointCloud2 msg;
  msg.header.frame_id = frame_id;
  msg.header.stamp = ros::Time(stamp_s);
  sensor_msgs::PointCloud2Modifier modifier(msg);
  modifier.setPointCloud2Fields(
      6, "x", 1, sensor_msgs::PointField::FLOAT32, "y", 1, sensor_msgs::PointField::FLOAT32, "z", 1,
      sensor_msgs::PointField::FLOAT32, "intensity", 1, sensor_msgs::PointField::FLOAT32, "ring", 1,
      sensor_msgs::PointField::UINT16, "truth_id", 1, sensor_msgs::PointField::UINT32);
  modifier.resize(f.full_points.size());
  msg.height = 1;
  msg.width = static_cast<std::uint32_t>(f.full_points.size());
  msg.is_dense = true;
  sensor_msgs::PointCloud2Iterator<float> x(msg, "x"), y(msg, "y"), z(msg, "z"), in(msg, "intensity");
  sensor_msgs::PointCloud2Iterator<std::uint16_t> ring(msg, "ring");
  sensor_msgs::PointCloud2Iterator<std::uint32_t> id(msg, "truth_id");
  for (std::size_t i = 0; i < f.full_points.size(); ++i, ++x, ++y, ++z, ++in, ++ring, ++id) {
    *x = f.full_points[i].x();
    *y = f.full_points[i].y();
    *z = f.full_points[i].z();
    *in = f.full_intensity[i];
    *ring = f.full_ring[i];
    *id = f.full_truth_id[i];
  }
  return msg;
}

}  // namespace

SyntheticBagWriter::SyntheticBagWriter(const std::string& path, SyntheticBagSettings settings,
                                       const syn::SyntheticConfig& config)
    : settings_(std::move(settings)), config_(config), info_template_(cameraInfoFromModel(config.rig.camera)) {
  info_template_.header.frame_id = settings_.camera_frame;
  bag_.open(path, rosbag::bagmode::Write);
  bag_.setCompression(rosbag::compression::LZ4);
  if (!settings_.camera_parent.empty()) {
    // One message before everything else (what a latched /tf_static looks like in a bag). The
    // camera's pose in its parent, as if the parent were the LiDAR frame: T_lidar_camera, the
    // same transform calibration_node publishes.
    const double stamp_s = config_.start_stamp_s - settings_.time_jitter_s - 0.01;
    tf2_msgs::TFMessage msg;
    msg.transforms.push_back(
        toTransformMsg(config_.rig.truth, settings_.camera_parent, settings_.camera_frame, ros::Time(stamp_s)));
    bag_.write("/tf_static", ros::Time(stamp_s), msg, latchedConnectionHeader<tf2_msgs::TFMessage>());
  }
}

void SyntheticBagWriter::write(const syn::SyntheticFrame& f) {
  const double jitter_s = settings_.time_jitter_s;
  std::mt19937_64 jitter_rng(syn::mixSeed(config_.seed, 11, static_cast<std::uint64_t>(f.index)));
  std::uniform_real_distribution<double> jitter(-jitter_s, jitter_s);
  auto stampFor = [&]() { return jitter_s > 0.0 ? f.stamp_s + jitter(jitter_rng) : f.stamp_s; };
  const double t_image = stampFor(), t_mask = stampFor(), t_clusters = stampFor();
  const std::string& camera_frame = settings_.camera_frame;
  const std::string& lidar_frame = settings_.lidar_frame;

  bag_.write("/thermal/image_raw", ros::Time(t_image), encodeMonoImage(f.image, camera_frame, t_image));
  if (settings_.camera_info) {
    sensor_msgs::CameraInfo info = info_template_;
    info.header.stamp = ros::Time(t_image);
    bag_.write("/thermal/camera_info", info.header.stamp, info);
  }
  bag_.write("/thermal/human_mask", ros::Time(t_mask), encodeMonoImage(f.mask, camera_frame, t_mask));
  // Per-point times (issue 21) go on every LiDAR cloud, the velodyne way.
  const bool times = config_.timing.lidar_point_time;
  auto timed = [&](const sensor_msgs::PointCloud2& cloud, const std::vector<float>& time_s) {
    return times ? withPointTimes(cloud, time_s) : cloud;
  };
  bag_.write("/lidar/human_clusters", ros::Time(t_clusters),
             timed(encodeClusters(f.cluster_points, f.cluster_labels, lidar_frame, t_clusters), f.cluster_time_s));
  if (config_.raw) {
    bag_.write("/lidar/points", ros::Time(t_clusters), timed(encodeRawScan(f, lidar_frame, t_clusters), f.full_time_s));
    bag_.write("/truth/thermal_person_ids", ros::Time(t_image),
               encodeMonoImage(f.truth_person_ids, camera_frame, t_image));
  } else if (config_.full_cloud) {
    bag_.write("/lidar/points", ros::Time(t_clusters),
               timed(encodePointsWithIntensity(f.full_points, f.full_intensity, lidar_frame, t_clusters),
                     f.full_time_s));
  }
}

void SyntheticBagWriter::close() { bag_.close(); }

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
