// FrameSynchronizer: message_filters ApproximateTime over (image, mask, clusters), behind a stamp
// guard.

#include "thermal_lidar_calibration/ros/frame_synchronizer.hpp"

#include <message_filters/sync_policies/approximate_time.h>
#include <message_filters/synchronizer.h>
#include <boost/function.hpp>
#include <boost/make_shared.hpp>
#include <ros/init.h>
#include <ros/time.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace thermal_lidar_calibration {
namespace ros_io {

using Policy = message_filters::sync_policies::ApproximateTime<
    sensor_msgs::Image, sensor_msgs::Image, sensor_msgs::PointCloud2>;

struct FrameSynchronizer::Impl {
  explicit Impl(int queue_size) : sync(Policy(static_cast<std::uint32_t>(queue_size))) {}
  message_filters::Synchronizer<Policy> sync;
};

FrameSynchronizer::FrameSynchronizer(int queue_size, double sync_slop_s, Callback callback)
    : callback_(std::move(callback)), queue_size_(queue_size), sync_slop_s_(sync_slop_s) {
  if (queue_size < 2) {
    throw std::invalid_argument("sync_queue_size = " + std::to_string(queue_size) +
                                ": must be at least 2");
  }
  if (!(sync_slop_s > 0.0) || !std::isfinite(sync_slop_s)) {
    throw std::invalid_argument("sync_slop = " + std::to_string(sync_slop_s) +
                                ": must be a positive number of seconds");
  }
  // message_filters stamps receipt times with ros::Time::now(), which aborts before
  // ros::Time::init(). A node has initialised it (possibly as sim time): leave that alone.
  if (!ros::isInitialized() && !ros::Time::isValid()) ros::Time::init();
  restart();
}

FrameSynchronizer::~FrameSynchronizer() = default;

// A fresh ApproximateTime (queues empty). Used at construction, when the data's time base
// moves, and when ApproximateTime failed half way through an update.
void FrameSynchronizer::restart() {
  impl_ = std::make_unique<Impl>(queue_size_);
  impl_->sync.setMaxIntervalDuration(ros::Duration(sync_slop_s_));
  // Signal9 wants all nine slots; the six unused ones carry message_filters::NullType.
  using NullPtr = const boost::shared_ptr<const message_filters::NullType>&;
  const boost::function<void(const sensor_msgs::Image::ConstPtr&,
                             const sensor_msgs::Image::ConstPtr&,
                             const sensor_msgs::PointCloud2::ConstPtr&, NullPtr, NullPtr, NullPtr,
                             NullPtr, NullPtr, NullPtr)>
      forward = [this](const sensor_msgs::Image::ConstPtr& image,
                       const sensor_msgs::Image::ConstPtr& mask,
                       const sensor_msgs::PointCloud2::ConstPtr& clusters, NullPtr, NullPtr,
                       NullPtr, NullPtr, NullPtr, NullPtr) {
        if (flushed_ && (image->header.stamp > latest_ || mask->header.stamp > latest_ ||
                         clusters->header.stamp > latest_)) {
          return;  // contains a flush() sentinel
        }
        ++triples_;
        if (!callback_) return;
        // An exception must not unwind through ApproximateTime (it would leave its queues half
        // updated): keep it and rethrow once add() has returned.
        try {
          callback_(image, mask, clusters);
        } catch (...) {
          if (!callback_error_) callback_error_ = std::current_exception();
        }
      };
  impl_->sync.registerCallback(forward);
}

template <int kSlot, typename Ptr>
FrameSynchronizer::AddOutcome FrameSynchronizer::add(const Ptr& msg) {
  AddOutcome outcome;
  if (!msg || flushed_) return {false, ""};
  const StampGuard::Decision decision = guard_.check(msg->header.stamp);
  if (decision.verdict == StampGuard::Verdict::kRefuse) {
    ++dropped_stamps_;
    return {false, decision.reason};
  }
  if (decision.verdict == StampGuard::Verdict::kMoveTimeBase) {
    restart();
    latest_ = ros::Time();
    outcome.fault = decision.reason;
  }
  latest_ = std::max(latest_, msg->header.stamp);
  try {
    impl_->sync.template add<kSlot>(msg);
  } catch (const std::exception& e) {
    // Last resort: the guard should make this unreachable.
    restart();
    outcome.fault = std::string("message pairing failed (") + e.what() +
                    "); the queued messages were dropped and pairing restarted";
  }
  if (callback_error_) {
    std::exception_ptr error = callback_error_;
    callback_error_ = nullptr;
    std::rethrow_exception(error);
  }
  return outcome;
}

FrameSynchronizer::AddOutcome FrameSynchronizer::addImage(const sensor_msgs::Image::ConstPtr& image) {
  return add<0>(image);
}
FrameSynchronizer::AddOutcome FrameSynchronizer::addMask(const sensor_msgs::Image::ConstPtr& mask) {
  return add<1>(mask);
}
FrameSynchronizer::AddOutcome FrameSynchronizer::addClusters(
    const sensor_msgs::PointCloud2::ConstPtr& clusters) {
  return add<2>(clusters);
}

void FrameSynchronizer::flush() {
  if (flushed_) return;
  flushed_ = true;
  // Far enough beyond the slop that no real message pairs with a sentinel (the guard keeps
  // latest_ clear of the end of ROS time, so this cannot overflow).
  const ros::Time sentinel = latest_ + ros::Duration(1000.0);
  auto image = boost::make_shared<sensor_msgs::Image>();
  image->header.stamp = sentinel;
  auto mask = boost::make_shared<sensor_msgs::Image>();
  mask->header.stamp = sentinel;
  auto clusters = boost::make_shared<sensor_msgs::PointCloud2>();
  clusters->header.stamp = sentinel;
  try {
    impl_->sync.add<0>(image);
    impl_->sync.add<1>(mask);
    impl_->sync.add<2>(clusters);
  } catch (const std::exception&) {
    // Nothing can follow a flush: a failure here only loses the last set.
  }
  if (callback_error_) {
    std::exception_ptr error = callback_error_;
    callback_error_ = nullptr;
    std::rethrow_exception(error);
  }
}

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
