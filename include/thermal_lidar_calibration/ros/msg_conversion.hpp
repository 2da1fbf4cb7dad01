#pragma once
// Pure conversions between ROS messages and core types. Every decode failure throws
// std::invalid_argument with one line saying what was wrong and what to do.

#include "thermal_lidar_calibration/app/parameters/point_time_field.hpp"
#include "thermal_lidar_calibration/core/calibration_pair.hpp"
#include "thermal_lidar_calibration/core/camera_model.hpp"
#include "thermal_lidar_calibration/ros/velocity_fields.hpp"

#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>

#include <string>

namespace thermal_lidar_calibration {
namespace ros_io {

// mono8/8UC1 -> CV_8UC1, mono16/16UC1 -> CV_16UC1 (deep copy). `topic` names the source in errors.
cv::Mat decodeMonoImage(const sensor_msgs::Image& msg, const std::string& topic);

struct DecodedClusters {
  std::vector<Eigen::Vector3f> points;  // finite points only
  std::vector<std::int32_t> labels;
  // Per point, seconds from the header stamp; empty when `time_field` selects no field.
  std::vector<float> point_time_s;
  // Per point, m/s relative to the LiDAR, when the cloud has the velocity fields a dataset bag
  // writes (velocity_fields.hpp); empty otherwise.
  std::vector<Eigen::Vector3f> point_velocity;
  // Per point, the standard errors of vx and vy (NaN: not measured), when the cloud has them too.
  std::vector<Eigen::Vector2f> point_velocity_se;
  std::size_t nonfinite_dropped = 0;    // points with a NaN/inf coordinate, label or time
};
// float32 x, y, z plus an integer (any int/uint width) or float `label` field, and the per-point
// capture times of the field `time_field` selects (issue 21). The field's type gives the unit:
// float32/float64 are seconds, relative to the header stamp (velodyne's `time`) or absolute
// (hesai's `timestamp`); int32/uint32 are nanoseconds relative to the stamp (ouster's `t`,
// livox's `offset_time`). A named field that is missing, or a chosen field of another type, is
// an error; auto finding none of its names is no per-point times.
DecodedClusters decodeClusters(const sensor_msgs::PointCloud2& msg, const std::string& topic,
                               const PointTimeField& time_field = {});

// Every finite point of a cloud with its index in the message (a raw scan for the person
// detector, whose output keeps each point's other fields: PersonDetectionAdapter).
struct DecodedCloud {
  std::vector<Eigen::Vector3f> points;
  std::vector<std::uint32_t> source_index;
};
DecodedCloud decodeCloud(const sensor_msgs::PointCloud2& msg, const std::string& topic);

// The clusters as one centroid per person (issue 21: the scans around a kept pair measure its
// people's motion), each centroid at its points' mean capture time. Throws
// std::invalid_argument as decodeClusters does.
ScanPeople decodeScanPeople(const sensor_msgs::PointCloud2& msg, const std::string& topic,
                            const PointTimeField& time_field = {});

// The finite x, y, z of every k-th point, k chosen so that at most about `max_points` are read
// (a full cloud for the overlay; other fields are ignored). The layout is checked exactly as
// decodeClusters checks it (one check for every cloud), so a declared size the data does not
// hold is an error, never a long loop or a read out of bounds.
std::vector<Eigen::Vector3f> decodeCloudPoints(const sensor_msgs::PointCloud2& msg,
                                               const std::string& topic, std::size_t max_points);

// K, size and plumb_bob (or empty/none) distortion. Throws on other models or a zero K.
CameraModel cameraModelFromMsg(const sensor_msgs::CameraInfo& msg);
sensor_msgs::CameraInfo cameraInfoFromModel(const CameraModel& camera);

// A header frame_id as tf2 accepts it: without leading '/' (tf1 style, as FieldSAFE's bags
// write them; tf2 rejects such ids, and "/velodyne" and "velodyne" are one sensor).
std::string tfFrameId(const std::string& frame_id);

// One synchronized candidate: image, mask and clusters decoded into a core Frame, with the
// clusters' stamp and the per-point times `time_field` selects.
Frame decodeFrame(const sensor_msgs::Image& image, const sensor_msgs::Image& mask,
                  const sensor_msgs::PointCloud2& clusters, const std::string& image_topic,
                  const std::string& mask_topic, const std::string& clusters_topic,
                  const PointTimeField& time_field = {});

// Encoders, for the generator and dataset bags.
sensor_msgs::Image encodeMonoImage(const cv::Mat& mat, const std::string& frame_id, double stamp_s);
sensor_msgs::PointCloud2 encodeClusters(const std::vector<Eigen::Vector3f>& points,
                                        const std::vector<std::int32_t>& labels,
                                        const std::string& frame_id, double stamp_s);
// float32 x, y, z, intensity (dense), e.g. a full LiDAR scan for /lidar/points.
sensor_msgs::PointCloud2 encodePointsWithIntensity(const std::vector<Eigen::Vector3f>& points,
                                                   const std::vector<float>& intensity,
                                                   const std::string& frame_id, double stamp_s);

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
