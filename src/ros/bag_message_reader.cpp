#include "thermal_lidar_calibration/ros/bag_message_reader.hpp"

#include <algorithm>
#include <utility>

namespace thermal_lidar_calibration {
namespace ros_io {
namespace {

// Messages a lane reads in one turn. A chunk cut by a turn's end is decompressed by both lanes;
// a bag recorded with rosbag's default 768 KB chunks holds a few images per chunk, so with 48
// messages a turn that repeats about a tenth of the decompression.
constexpr std::uint64_t kBlock = 48;
// What a lane holds ready: its next turn while the consumer reads the other lane's, and no more
// than kReadAheadBytes of message data (a raw cloud is 2 MB, and a lane that runs ahead only
// spends memory: the consumer sets the pace).
constexpr std::size_t kReadAhead = kBlock;
constexpr std::size_t kReadAheadBytes = std::size_t{16} << 20;

std::size_t laneOf(std::uint64_t index, std::size_t lanes) { return (index / kBlock) % lanes; }

std::size_t dataBytes(const BagMessage& m) {
  return (m.image ? m.image->data.size() : 0) + (m.cloud ? m.cloud->data.size() : 0);
}

}  // namespace

BagMessageReader::BagMessageReader(rosbag::Bag& bag, const std::vector<std::string>& topics,
                                   const std::vector<std::string>& cloud_topics, int lanes)
    : cloud_topics_(cloud_topics) {
  auto first = std::make_unique<Lane>();
  first->view = std::make_unique<rosbag::View>(bag, rosbag::TopicQuery(topics));
  size_ = first->view->size();
  lanes_.push_back(std::move(first));
  // The same query on the same file lists the same messages in the same order: each lane walks
  // the whole list (an index walk, no decompression) and reads only its own turns.
  for (int k = 1; k < lanes; ++k) {
    auto lane = std::make_unique<Lane>();
    try {
      lane->own_bag = std::make_unique<rosbag::Bag>();
      lane->own_bag->open(bag.getFileName(), rosbag::bagmode::Read);
      lane->view = std::make_unique<rosbag::View>(*lane->own_bag, rosbag::TopicQuery(topics));
    } catch (const std::exception&) {
      break;  // fewer lanes read the same messages
    }
    if (lane->view->size() != size_) break;
    lanes_.push_back(std::move(lane));
  }
  try {
    for (std::size_t k = 0; k < lanes_.size(); ++k) lanes_[k]->thread = std::thread([this, k] { run(k); });
  } catch (...) {  // no thread to be had: stop those started, which the destructor will not
    stopAndJoin();
    throw;
  }
}

BagMessageReader::~BagMessageReader() { stopAndJoin(); }

void BagMessageReader::stopAndJoin() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  changed_.notify_all();
  for (auto& lane : lanes_) {
    if (lane->thread.joinable()) lane->thread.join();
  }
}

bool BagMessageReader::next(BagMessage& out) {
  Lane& lane = *lanes_[laneOf(taken_, lanes_.size())];
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait(lock, [&lane] { return !lane.queue.empty() || lane.done; });
  if (lane.queue.empty()) return false;  // this lane, which holds the next message, has none
  out = std::move(lane.queue.front());
  lane.queue.pop_front();
  lane.queued_bytes -= dataBytes(out);
  ++taken_;
  changed_.notify_all();
  return true;
}

std::string BagMessageReader::damage() {
  // The lane that holds the message next() hands out next; empty while that lane still reads.
  const Lane& lane = *lanes_[laneOf(taken_, lanes_.size())];
  std::lock_guard<std::mutex> lock(mutex_);
  return lane.done && lane.queue.empty() ? lane.damage : std::string();
}

// A message that cannot be deserialised (a truncated record, a damaged chunk) is passed on as
// such, to be counted and skipped where it is read; a view that cannot go on ends the reading.
BagMessage BagMessageReader::load(const rosbag::MessageInstance& m) const {
  BagMessage message;
  message.topic = m.getTopic();
  message.time_s = m.getTime().toSec();
  try {
    if (std::find(cloud_topics_.begin(), cloud_topics_.end(), message.topic) != cloud_topics_.end()) {
      message.cloud = m.instantiate<sensor_msgs::PointCloud2>();
    } else {
      message.image = m.instantiate<sensor_msgs::Image>();
    }
  } catch (const ros::Exception& e) {
    message.undecodable = e.what();
  }
  return message;
}

bool BagMessageReader::push(Lane& lane, BagMessage message) {
  const std::size_t bytes = dataBytes(message);
  std::unique_lock<std::mutex> lock(mutex_);
  // An empty queue always takes the next message, however large: the consumer may be waiting.
  changed_.wait(lock, [&] {
    return stopping_ || lane.queue.empty() ||
           (lane.queue.size() < kReadAhead && lane.queued_bytes + bytes <= kReadAheadBytes);
  });
  if (stopping_) return false;
  lane.queued_bytes += bytes;
  lane.queue.push_back(std::move(message));
  changed_.notify_all();
  return true;
}

void BagMessageReader::run(std::size_t lane_index) {
  Lane& lane = *lanes_[lane_index];
  std::string damage;
  try {
    std::uint64_t index = 0;
    for (auto it = lane.view->begin(); it != lane.view->end(); ++it, ++index) {
      if (laneOf(index, lanes_.size()) != lane_index) continue;
      if (!push(lane, load(*it))) break;
    }
  } catch (const std::exception& e) {
    damage = e.what();
    if (damage.empty()) damage = "unreadable record";
  } catch (...) {  // nothing may leave a thread: that would end the process
    damage = "unreadable record";
  }
  std::lock_guard<std::mutex> lock(mutex_);
  lane.done = true;
  lane.damage = damage;
  changed_.notify_all();
}

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
