#pragma once
// Appends groups of messages to a ROS 1 bag (format 2.0) at a cost that does not grow with the
// bag, and never leaves it unreadable.
//
// Why not rosbag::Bag's append mode: it does not reuse the bag's connections (every append added
// one connection record per topic, each with its full message definition, ~3 KB), and it reads
// the whole index on open and writes it again on close, so an append at pair 500 cost 9x one at
// pair 5 (issue 12). This writer keeps the bag's index in memory (one connection record per
// topic, one ~150-byte chunk-info record per group) and writes each group as one LZ4 chunk where
// the old index was, then the new index and the file header. rosbag reads the result as any bag
// (the tests read it with rosbag::View; `rosbag info` and `rosbag reindex` accept it).
//
// Crash safety: before an append overwrites anything, the bytes it overwrites (the file header
// and the old index) go to "<bag>.journal"; after the append the journal is deleted, and
// recoverBagAppend() puts them back if it is still there. A new bag is written as "<bag>.tmp" and
// renamed. So a kill at any moment leaves a bag with every group whose append() returned.

#include <ros/message_traits.h>
#include <ros/serialization.h>
#include <ros/time.h>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace thermal_lidar_calibration {
namespace ros_io {

class BagAppender {
 public:
  // One message of a group, serialized, with what its connection record needs.
  struct Message {
    std::string topic;
    ros::Time time;
    std::string datatype, md5sum, definition;
    std::vector<std::uint8_t> bytes;
  };
  template <class M>
  static Message message(std::string topic, ros::Time time, const M& msg) {
    Message m{std::move(topic), time, ros::message_traits::datatype(msg),
              ros::message_traits::md5sum(msg), ros::message_traits::definition(msg), {}};
    m.bytes.resize(ros::serialization::serializationLength(msg));
    ros::serialization::OStream stream(m.bytes.data(), static_cast<std::uint32_t>(m.bytes.size()));
    ros::serialization::serialize(stream, msg);
    return m;
  }

  // Continues the bag at `path` when it exists (recovered first; its index is read once), else
  // starts a new bag with the first append. Throws std::runtime_error naming the path when the
  // existing file is not a bag it can continue.
  explicit BagAppender(std::string path);

  // Appends the group as one chunk; returns when it is in the file. Throws std::runtime_error
  // naming the path and the reason; the bag then holds what it held before.
  void append(const std::vector<Message>& group);

  const std::string& path() const { return path_; }
  // The bag's index (connection and chunk-info records): what every append rewrites.
  std::size_t indexBytes() const { return connection_records_.size() + chunk_infos_.size(); }

 private:
  void readIndex();
  std::string fileHeader(std::uint64_t index_pos, std::uint32_t chunks) const;
  void writeNew(const std::string& header, const std::string& tail);
  void writeInPlace(const std::string& old_header, const std::string& header,
                    const std::string& tail);

  std::string path_;
  bool exists_ = false;
  std::uint64_t index_pos_ = 0;
  std::uint64_t file_size_ = 0;
  std::map<std::string, std::uint32_t> connection_ids_;  // topic -> connection id
  std::uint32_t connection_count_ = 0;
  std::uint32_t next_connection_id_ = 0;
  std::uint32_t chunk_count_ = 0;
  std::string connection_records_;  // the index, as it is in the file
  std::string chunk_infos_;
};

// If "<path>.journal" exists (the process died during an append), restores the bag from it.
// Returns true if a restore happened. Throws std::runtime_error if the journal is unusable.
bool recoverBagAppend(const std::string& path);

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
