// BagMessageReader: whatever the lanes, the messages come out as a rosbag::View lists them (ties
// in receive time included), each deserialised as its topic's type; a message that cannot be
// deserialised is passed on as such and the reading goes on; a reader dropped half way stops.

#include "thermal_lidar_calibration/ros/bag_message_reader.hpp"

#include "../support/test_files.hpp"

#include <rosbag/bag.h>
#include <rosbag/view.h>

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace tlc = thermal_lidar_calibration;
using tlc::ros_io::BagMessage;
using tlc::ros_io::BagMessageReader;

namespace {

const std::vector<std::string> kTopics = {"/image", "/mask", "/clusters"};
const std::vector<std::string> kClouds = {"/clusters"};

// Each message carries its number in frame_id ("m<number>") and data, so that order and content
// can be checked after any reading.
template <typename Message>
Message numbered(int number, double stamp_s, std::size_t bytes) {
  Message m;
  m.header.stamp.fromSec(stamp_s);
  m.header.frame_id = "m" + std::to_string(number);
  m.data.assign(bytes, static_cast<std::uint8_t>(number));
  return m;
}

sensor_msgs::Image image(int number, double stamp_s) {
  auto m = numbered<sensor_msgs::Image>(number, stamp_s, 32);
  m.height = 4;
  m.width = 8;
  m.encoding = "mono8";
  m.step = 8;
  return m;
}

sensor_msgs::PointCloud2 cloud(int number, double stamp_s) {
  auto m = numbered<sensor_msgs::PointCloud2>(number, stamp_s, 12);
  m.height = 1;
  m.width = 3;
  m.point_step = 4;
  m.row_step = 12;
  return m;
}

// `frames` frames of image, mask (the image's receive time: a tie) and clusters, small chunks so
// that the reading crosses many, and a topic nobody asks for in between.
std::string writeBag(const std::string& dir, int frames, rosbag::compression::CompressionType compression) {
  const std::string path = dir + "/messages.bag";
  rosbag::Bag bag(path, rosbag::bagmode::Write);
  bag.setCompression(compression);
  bag.setChunkThreshold(2048);
  int number = 0;
  for (int f = 0; f < frames; ++f) {
    const double t = 100.0 + 0.1 * f;
    const ros::Time at = ros::Time().fromSec(t);
    bag.write("/image", at, image(number++, t));
    bag.write("/mask", at, image(number++, t));
    bag.write("/other", at, image(number++, t));
    bag.write("/clusters", ros::Time().fromSec(t + 0.03), cloud(number++, t + 0.03));
  }
  bag.close();
  return path;
}

std::vector<std::string> readAll(const std::string& path, int lanes, int* lanes_used = nullptr,
                                 std::vector<std::string>* undecodable = nullptr) {
  rosbag::Bag bag(path, rosbag::bagmode::Read);
  BagMessageReader reader(bag, kTopics, kClouds, lanes);
  if (lanes_used) *lanes_used = reader.lanes();
  std::vector<std::string> seen;
  BagMessage m;
  while (reader.next(m)) {
    if (!m.undecodable.empty()) {
      if (undecodable) undecodable->push_back(m.topic + " " + m.undecodable);
      seen.push_back(m.topic + " undecodable");
    } else if (m.topic == "/clusters") {
      EXPECT_TRUE(m.cloud && !m.image) << m.topic;
      seen.push_back(m.topic + " " + (m.cloud ? m.cloud->header.frame_id : "null"));
    } else {
      EXPECT_TRUE(m.image && !m.cloud) << m.topic;
      seen.push_back(m.topic + " " + (m.image ? m.image->header.frame_id : "null"));
    }
  }
  EXPECT_EQ(reader.damage(), "");
  EXPECT_EQ(seen.size(), reader.size());
  return seen;
}

std::vector<std::string> readWithView(const std::string& path) {
  rosbag::Bag bag(path, rosbag::bagmode::Read);
  rosbag::View view(bag, rosbag::TopicQuery(kTopics));
  std::vector<std::string> seen;
  for (const rosbag::MessageInstance& m : view) {
    seen.push_back(m.getTopic() + " " +
                   (m.getTopic() == "/clusters" ? m.instantiate<sensor_msgs::PointCloud2>()->header.frame_id
                                                : m.instantiate<sensor_msgs::Image>()->header.frame_id));
  }
  return seen;
}

}  // namespace

TEST(BagMessageReader, ReadsWhatAViewListsInItsOrderWithEveryNumberOfLanes) {
  const std::string dir = tlc::test_support::tempDir("tlc_reader_");
  for (const auto compression : {rosbag::compression::Uncompressed, rosbag::compression::LZ4}) {
    const std::string path = writeBag(dir, 90, compression);  // 270 wanted messages: 6 turns of 48
    const std::vector<std::string> expected = readWithView(path);
    ASSERT_EQ(expected.size(), 270u);
    for (const int lanes : {1, 2, 3}) {
      int used = 0;
      EXPECT_EQ(readAll(path, lanes, &used), expected) << lanes << " lanes";
      EXPECT_EQ(used, lanes);
    }
  }
}

TEST(BagMessageReader, PassesOnAMessageThatCannotBeDeserialisedAndReadsOn) {
  const std::string dir = tlc::test_support::tempDir("tlc_reader_");
  const std::string path = writeBag(dir, 90, rosbag::compression::Uncompressed);
  const std::vector<std::string> expected = readWithView(path);
  // The data length of the mask numbered 101, in the file itself: after its frame_id come
  // height, width, encoding ("mono8"), is_bigendian and step (4 + 4 + 4 + 5 + 1 + 4 bytes).
  std::string bytes;
  {
    std::ifstream in(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  const std::string marker = std::string("\x04\x00\x00\x00", 4) + "m101";
  const std::size_t at = bytes.find(marker);
  ASSERT_NE(at, std::string::npos);
  ASSERT_EQ(bytes.find(marker, at + 1), std::string::npos);
  const std::uint32_t huge = 1000000;  // longer than the record: deserialising it overruns
  std::memcpy(&bytes[at + marker.size() + 22], &huge, sizeof(huge));
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;

  for (const int lanes : {1, 2}) {
    std::vector<std::string> undecodable;
    const std::vector<std::string> seen = readAll(path, lanes, nullptr, &undecodable);
    ASSERT_EQ(seen.size(), expected.size()) << lanes << " lanes";
    ASSERT_EQ(undecodable.size(), 1u) << lanes << " lanes";
    EXPECT_EQ(undecodable[0].rfind("/mask ", 0), 0u) << undecodable[0];
    for (std::size_t i = 0; i < seen.size(); ++i) {
      if (expected[i] == "/mask m101") {
        EXPECT_EQ(seen[i], "/mask undecodable");
      } else {
        EXPECT_EQ(seen[i], expected[i]) << i;
      }
    }
  }
}

// Its lanes fill their read-ahead and wait: dropping the reader must wake and end them.
TEST(BagMessageReader, StopsWhenDroppedHalfWay) {
  const std::string dir = tlc::test_support::tempDir("tlc_reader_");
  const std::string path = writeBag(dir, 200, rosbag::compression::LZ4);
  const std::vector<std::string> expected = readWithView(path);
  rosbag::Bag bag(path, rosbag::bagmode::Read);
  {
    BagMessageReader reader(bag, kTopics, kClouds, 2);
    BagMessage m;
    for (int i = 0; i < 5; ++i) ASSERT_TRUE(reader.next(m));
    ASSERT_TRUE(m.image);
    EXPECT_EQ(m.topic + " " + m.image->header.frame_id, expected[4]);
  }
  // The bag handle is the caller's again, and whole.
  rosbag::View view(bag, rosbag::TopicQuery(kTopics));
  EXPECT_EQ(view.size(), 600u);
}
