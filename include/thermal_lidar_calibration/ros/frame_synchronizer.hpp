#pragma once
// The one pairing rule of image, mask and clusters, shared by calibration_node (subscriber
// callbacks) and calibrate_bag (bag messages): message_filters ApproximateTime with a queue size
// and a maximum interval (sync_slop). Feed it messages; it calls back with matched triples.
// Stamps that would break ApproximateTime's arithmetic are refused first (StampGuard), and a
// failure inside ApproximateTime restarts it instead of leaving it half-updated, so no message,
// however malformed its header, ends the caller.

#include "thermal_lidar_calibration/ros/stamp_guard.hpp"

#include <sensor_msgs/Image.h>
#include <ros/time.h>
#include <sensor_msgs/PointCloud2.h>

#include <cstdint>
#include <exception>
#include <functional>
#include <memory>
#include <optional>
#include <string>

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

  struct AddOutcome {
    bool added = true;
    // Why the message was refused, or what happened to the queued messages (the time base
    // moved, or ApproximateTime failed and was restarted); one line, without the topic.
    std::string fault;
  };
  // Exceptions thrown by the callback reach the caller of add*() after ApproximateTime has
  // finished its update.
  AddOutcome addImage(const sensor_msgs::Image::ConstPtr& image);
  AddOutcome addMask(const sensor_msgs::Image::ConstPtr& mask);
  AddOutcome addClusters(const sensor_msgs::PointCloud2::ConstPtr& clusters);

  // End of input (offline only): releases the last complete set, which ApproximateTime
  // otherwise holds until a later message proves it optimal. Feeds one empty sentinel per topic
  // far in the future; a set made of sentinels is never passed on. Add nothing afterwards.
  void flush();

  std::uint64_t triples() const { return triples_; }  // callbacks made so far
  std::uint64_t droppedStamps() const { return dropped_stamps_; }  // messages refused
  // The latest accepted header stamp: the data's own time (not the wall or ROS clock).
  std::optional<ros::Time> dataTime() const { return guard_.dataTime(); }

 private:
  struct Impl;
  template <int kSlot, typename Ptr>
  AddOutcome add(const Ptr& msg);
  void restart();
  std::unique_ptr<Impl> impl_;
  Callback callback_;
  int queue_size_;
  double sync_slop_s_;
  StampGuard guard_;
  std::exception_ptr callback_error_;  // thrown by callback_ inside ApproximateTime
  std::uint64_t triples_ = 0;
  std::uint64_t dropped_stamps_ = 0;
  ros::Time latest_;  // latest header stamp added, for flush()
  bool flushed_ = false;
};

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
