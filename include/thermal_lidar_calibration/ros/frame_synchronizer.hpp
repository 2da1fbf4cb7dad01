#pragma once
// The one pairing rule of image, mask and clusters, shared by calibration_node (subscriber
// callbacks) and calibrate_bag (bag messages): message_filters ApproximateTime with a queue size
// and a maximum interval (sync_slop). Feed it messages; it calls back with matched triples.

#include <sensor_msgs/Image.h>
#include <ros/time.h>
#include <sensor_msgs/PointCloud2.h>

#include <cstdint>
#include <functional>
#include <memory>

namespace thermal_lidar_calibration {
namespace ros_io {

class FrameSynchronizer {
 public:
  using Callback = std::function<void(const sensor_msgs::Image::ConstPtr& image,
                                      const sensor_msgs::Image::ConstPtr& mask,
                                      const sensor_msgs::PointCloud2::ConstPtr& clusters)>;

  // queue_size >= 2, sync_slop_s > 0 (throws std::invalid_argument otherwise). When ROS is not
  // initialised (offline tools), initialises ros::Time with the wall clock, which
  // message_filters needs.
  FrameSynchronizer(int queue_size, double sync_slop_s, Callback callback);
  ~FrameSynchronizer();
  FrameSynchronizer(const FrameSynchronizer&) = delete;
  FrameSynchronizer& operator=(const FrameSynchronizer&) = delete;

  void addImage(const sensor_msgs::Image::ConstPtr& image);
  void addMask(const sensor_msgs::Image::ConstPtr& mask);
  void addClusters(const sensor_msgs::PointCloud2::ConstPtr& clusters);

  // End of input (offline only): releases the last complete set, which ApproximateTime
  // otherwise holds until a later message proves it optimal. Feeds one empty sentinel per topic
  // far in the future; a set made of sentinels is never passed on. Add nothing afterwards.
  void flush();

  std::uint64_t triples() const { return triples_; }  // callbacks made so far

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  Callback callback_;
  std::uint64_t triples_ = 0;
  ros::Time latest_;  // latest header stamp added, for flush()
  bool flushed_ = false;
};

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
