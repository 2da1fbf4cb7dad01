#pragma once
// A bag's messages read ahead on threads of their own. Decompressing a bag's chunks (roslz4
// checksums every byte) and deserialising its messages took twice as long as everything the
// ingest then does with them, and calibrate_bag did both in turn on one core while the other
// stood idle. Here two lanes, each with its own handle on the file, take turns by blocks of
// messages; the messages still come out one by one in the order a rosbag::View gives them,
// whatever the threads do, so what is read is exactly what reading in line would read.

#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace thermal_lidar_calibration {
namespace ros_io {

struct BagMessage {
  std::string topic;
  double time_s = 0.0;                       // the bag's receive time
  sensor_msgs::Image::ConstPtr image;        // on an image topic (null: another type recorded)
  sensor_msgs::PointCloud2::ConstPtr cloud;  // on a cloud topic (null: another type recorded)
  std::string undecodable;                   // why it could not be deserialised, if it could not
};

class BagMessageReader {
 public:
  // Reads `topics` of `bag`, those in `cloud_topics` as PointCloud2 and the others as Image, on
  // up to `lanes` threads (one more handle on bag.getFileName() each after the first; one lane
  // if the file cannot be opened again). Nothing else may use `bag` until the reader is
  // destroyed. Throws what rosbag::View throws.
  BagMessageReader(rosbag::Bag& bag, const std::vector<std::string>& topics,
                   const std::vector<std::string>& cloud_topics, int lanes = 2);
  ~BagMessageReader();  // stops reading and joins the threads
  BagMessageReader(const BagMessageReader&) = delete;
  BagMessageReader& operator=(const BagMessageReader&) = delete;

  std::uint64_t size() const { return size_; }  // messages the view holds
  int lanes() const { return static_cast<int>(lanes_.size()); }
  // The next message in bag order; false at the end, or where the bag could not be read past
  // (then damage() says why).
  bool next(BagMessage& out);
  std::string damage();  // why next() returned false; empty at the end or while reading goes on

 private:
  struct Lane {
    std::unique_ptr<rosbag::Bag> own_bag;  // the lanes after the first
    std::unique_ptr<rosbag::View> view;
    std::deque<BagMessage> queue;
    std::size_t queued_bytes = 0;  // the queue's message data
    bool done = false;  // read its last message, or could not go on (damage)
    std::string damage;
    std::thread thread;
  };
  void run(std::size_t lane_index);
  void stopAndJoin();
  BagMessage load(const rosbag::MessageInstance& m) const;
  bool push(Lane& lane, BagMessage message);  // false once the reader is being destroyed

  const std::vector<std::string> cloud_topics_;
  std::uint64_t size_ = 0;
  std::uint64_t taken_ = 0;  // messages next() has handed out
  std::mutex mutex_;
  std::condition_variable changed_;
  bool stopping_ = false;  // the consumer is gone
  std::vector<std::unique_ptr<Lane>> lanes_;
};

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
