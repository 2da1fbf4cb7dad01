// DatasetBagWriter: every pair whose write() returned is in the bag, also when the disk fills
// (simulated with RLIMIT_FSIZE: a write past the limit fails with EFBIG, as ENOSPC would) and
// when the process is killed at any moment; an append costs the same however many pairs the bag
// holds (one connection per topic, the index grows by one chunk-info record per pair); rosbag
// reads the bag, and a bag written by rosbag itself (older versions of the node) is continued.

#include "thermal_lidar_calibration/ros/dataset_bag.hpp"
#include "thermal_lidar_calibration/ros/msg_conversion.hpp"

#include "../support/dataset_pair_messages.hpp"
#include "../support/test_files.hpp"

#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <std_msgs/String.h>

#include <gtest/gtest.h>

#include <poll.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <random>
#include <set>
#include <string>
#include <thread>

namespace tlc = thermal_lidar_calibration;
using tlc::ros_io::DatasetBagWriter;

namespace {

using tlc::test_support::PairMessages;

PairMessages makePair(double stamp_s, unsigned seed) {
  return tlc::test_support::makePairMessages(stamp_s, seed);
}

void write(DatasetBagWriter& writer, const PairMessages& m) {
  writer.write(m.image, m.mask, m.clusters, m.info);
}

// Runs `body` in a child process whose files may not grow past `limit_bytes`; SIGXFSZ is ignored
// so that the write fails with EFBIG instead of killing it. Returns the child's wait status.
int runWithFileSizeLimit(rlim_t limit_bytes, const std::function<int()>& body) {
  std::fflush(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) {
    std::signal(SIGXFSZ, SIG_IGN);
    const rlimit limit{limit_bytes, limit_bytes};
    ::setrlimit(RLIMIT_FSIZE, &limit);
    std::_Exit(body());
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  return status;
}

}  // namespace

// A disk that fills during an append: write() throws (the node then stops recording) instead of
// ending the process (rosbag::Bag's destructor used to throw again: std::terminate), and the bag
// still holds every pair written before.
TEST(DatasetBagWriter, FullDiskIsAnErrorAndEarlierPairsSurvive) {
  const std::string dir = tlc::test_support::tempDir("tlc_dataset_full_");
  const std::string path = dir + "/dataset.bag";
  constexpr int kAttempts = 12;
  const int status = runWithFileSizeLimit(3u << 20, [&] {
    int written = 0;
    try {
      DatasetBagWriter writer(path, false);
      for (; written < kAttempts; ++written) write(writer, makePair(100.0 + written, written));
    } catch (const std::runtime_error& e) {
      std::fprintf(stderr, "write %d failed as expected: %s\n", written + 1, e.what());
      return written;
    }
    return 100;  // the limit was never reached: the test is wrong
  });
  ASSERT_TRUE(WIFEXITED(status)) << "the writer ended the process (signal "
                                 << (WIFSIGNALED(status) ? WTERMSIG(status) : 0) << ")";
  const int written = WEXITSTATUS(status);
  ASSERT_LT(written, kAttempts) << "the file size limit was never reached";
  ASSERT_GE(written, 1);
  const auto contents = tlc::ros_io::readDatasetBag(path);
  EXPECT_EQ(static_cast<int>(contents.frames.size()), written);
  EXPECT_TRUE(contents.errors.empty());
  std::filesystem::remove_all(dir);
}

namespace {

// A child process running `body`, which calls ack() after each pair it wrote; the parent reads
// the acknowledgements from `acks_fd` (countAcks) once the child is gone.
struct AckingChild {
  pid_t pid;
  int acks_fd;
};
AckingChild forkAckingChild(const std::function<void(const std::function<void()>& ack)>& body) {
  int fds[2];
  if (::pipe(fds) != 0) throw std::runtime_error("pipe failed");
  std::fflush(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(fds[0]);
    body([&] {
      const char ack = 1;
      if (::write(fds[1], &ack, 1) != 1) std::_Exit(3);
    });
    std::_Exit(0);
  }
  ::close(fds[1]);
  return {pid, fds[0]};
}

int countAcks(int fd) {
  int count = 0;
  char acks[4096];
  for (ssize_t n; (n = ::read(fd, acks, sizeof(acks))) > 0;) count += static_cast<int>(n);
  ::close(fd);
  return count;
}

// Reads acknowledgements from `fd` until `wanted` have come; returns how many came (fewer only
// when the child stopped acknowledging for `hang_guard_s`: a deadline against hangs, not a clock).
int readAcks(int fd, int wanted, double hang_guard_s) {
  int count = 0;
  while (count < wanted) {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, static_cast<int>(hang_guard_s * 1000)) <= 0) break;
    char acks[64];
    const ssize_t n = ::read(fd, acks, std::min<std::size_t>(sizeof(acks), static_cast<std::size_t>(wanted - count)));
    if (n <= 0) break;
    count += static_cast<int>(n);
  }
  return count;
}

std::size_t connectionsIn(const std::string& path) {
  rosbag::Bag bag(path, rosbag::bagmode::Read);
  return rosbag::View(bag).getConnections().size();
}

}  // namespace

// Issue 12 item 9: rosbag's append mode added 5 connection records (~15 KB with their message
// definitions) per pair and rewrote them all on every append. Now the bag has one connection per
// topic, and each pair adds one chunk-info record (< 200 bytes) to the index an append rewrites.
TEST(DatasetBagWriter, AnAppendAddsOnlyOneSmallIndexRecord) {
  const std::string dir = tlc::test_support::tempDir("tlc_dataset_index_");
  const std::string path = dir + "/dataset.bag";
  DatasetBagWriter writer(path, false);
  write(writer, makePair(100.0, 0));
  const std::size_t index_after_one = writer.indexBytes();
  for (int i = 1; i < 40; ++i) write(writer, makePair(100.0 + i, i % 3));
  EXPECT_EQ(connectionsIn(path), 5u);
  const double per_pair = static_cast<double>(writer.indexBytes() - index_after_one) / 39.0;
  EXPECT_LT(per_pair, 200.0) << "the index grows by " << per_pair << " bytes per pair";
  EXPECT_EQ(tlc::ros_io::countDatasetBag(path).pairs, 40u);
  // A writer that continues the bag (~resume) reuses its connections too.
  DatasetBagWriter resumed(path, true);
  write(resumed, makePair(200.0, 1));
  EXPECT_EQ(connectionsIn(path), 5u);
  EXPECT_EQ(tlc::ros_io::countDatasetBag(path).pairs, 41u);
}

// What rosbag reads back is what was written: the messages, their types, topics and times.
TEST(DatasetBagWriter, RosbagReadsEveryMessageAsWritten) {
  const std::string dir = tlc::test_support::tempDir("tlc_dataset_read_");
  const std::string path = dir + "/dataset.bag";
  std::vector<PairMessages> pairs;
  {
    DatasetBagWriter writer(path, false);
    for (int i = 0; i < 3; ++i) {
      pairs.push_back(makePair(1600000000.0 + 0.5 * i, i));
      write(writer, pairs.back());
    }
  }
  rosbag::Bag bag(path, rosbag::bagmode::Read);
  rosbag::View view(bag);
  std::size_t images = 0, messages = 0;
  std::set<std::string> topics;
  for (const rosbag::MessageInstance& m : view) {
    ++messages;
    topics.insert(m.getTopic());
    if (m.getTopic() != tlc::ros_io::DatasetBagTopics::kImage) continue;
    const auto image = m.instantiate<sensor_msgs::Image>();
    ASSERT_TRUE(image);
    ASSERT_LT(images, pairs.size());
    EXPECT_EQ(m.getTime(), pairs[images].image.header.stamp);
    EXPECT_EQ(image->data, pairs[images].image.data);
    EXPECT_EQ(image->encoding, "mono16");
    ++images;
  }
  EXPECT_EQ(images, 3u);
  EXPECT_EQ(messages, 15u);
  EXPECT_EQ(topics.size(), 5u);
  const auto contents = tlc::ros_io::readDatasetBag(path);
  EXPECT_EQ(contents.frames.size(), 3u);
  EXPECT_TRUE(contents.errors.empty());
}

// A dataset bag written by rosbag::Bag (the node before this writer, in append mode) is continued.
TEST(DatasetBagWriter, ContinuesABagWrittenByRosbag) {
  const std::string dir = tlc::test_support::tempDir("tlc_dataset_old_");
  const std::string path = dir + "/dataset.bag";
  for (int i = 0; i < 2; ++i) {
    const PairMessages m = makePair(100.0 + i, i);
    rosbag::Bag bag(path, i == 0 ? rosbag::bagmode::Write : rosbag::bagmode::Append);
    bag.setCompression(rosbag::compression::LZ4);
    std_msgs::String marker;
    marker.data = "pair";
    const ros::Time t = m.image.header.stamp;
    bag.write(tlc::ros_io::DatasetBagTopics::kCameraInfo, t, m.info);
    bag.write(tlc::ros_io::DatasetBagTopics::kImage, t, m.image);
    bag.write(tlc::ros_io::DatasetBagTopics::kMask, t, m.mask);
    bag.write(tlc::ros_io::DatasetBagTopics::kClusters, t, m.clusters);
    bag.write(tlc::ros_io::DatasetBagTopics::kMarker, t, marker);
  }
  ASSERT_EQ(connectionsIn(path), 10u);  // rosbag's append added a second set
  DatasetBagWriter writer(path, true);
  for (int i = 2; i < 4; ++i) write(writer, makePair(100.0 + i, i));
  EXPECT_EQ(connectionsIn(path), 10u);
  const auto contents = tlc::ros_io::readDatasetBag(path);
  EXPECT_EQ(contents.frames.size(), 4u);
  EXPECT_TRUE(contents.errors.empty());
}

// Pairing by association: the frames held as candidates, and the skipped frames held for the
// final round (issue 24), are stored with the pairs, each with its kind and its place among the
// frames offered; countDatasetBag counts the three apart, and a marker from before the frame
// number was recorded reads as a pair in order.
TEST(DatasetBagWriter, StoresAssociationCandidatesWithTheirKindAndPlace) {
  const std::string dir = tlc::test_support::tempDir("tlc_dataset_kinds_");
  const std::string path = dir + "/dataset.bag";
  {
    DatasetBagWriter writer(path, false);
    const PairMessages a = makePair(100.0, 1), b = makePair(100.4, 2), c = makePair(101.0, 3),
                       d = makePair(101.1, 4);
    writer.write(a.image, a.mask, a.clusters, a.info, {false, 8});
    writer.write(b.image, b.mask, b.clusters, b.info, {true, 12});
    writer.write(c.image, c.mask, c.clusters, c.info, {false, 17});
    writer.write(d.image, d.mask, d.clusters, d.info, {true, 18, true});
  }
  const auto contents = tlc::ros_io::readDatasetBag(path);
  ASSERT_EQ(contents.frames.size(), 4u);
  ASSERT_EQ(contents.kinds.size(), 4u);
  EXPECT_FALSE(contents.kinds[0].skipped);
  EXPECT_FALSE(contents.kinds[1].skipped);
  EXPECT_TRUE(contents.kinds[3].candidate);
  EXPECT_TRUE(contents.kinds[3].skipped);
  EXPECT_EQ(contents.kinds[3].frame_index, 18u);
  EXPECT_EQ(tlc::ros_io::countDatasetBag(path).skipped_frames, 1u);
  EXPECT_FALSE(contents.kinds[0].candidate);
  EXPECT_EQ(contents.kinds[0].frame_index, 8u);
  EXPECT_TRUE(contents.kinds[1].candidate);
  EXPECT_EQ(contents.kinds[1].frame_index, 12u);
  EXPECT_EQ(contents.kinds[2].frame_index, 17u);
  EXPECT_EQ(tlc::ros_io::countDatasetBag(path).pairs, 2u);
  EXPECT_EQ(tlc::ros_io::countDatasetBag(path).candidates, 1u);

  const tlc::StoredFrameKind old_pair = tlc::ros_io::parseDatasetMarker("pair kept by calibration_node (already gated)");
  EXPECT_FALSE(old_pair.candidate);
  EXPECT_FALSE(old_pair.frame_index.has_value());
  EXPECT_FALSE(tlc::ros_io::parseDatasetMarker("pair").frame_index.has_value());
  EXPECT_FALSE(tlc::ros_io::parseDatasetMarker("pair; frame 12x").frame_index.has_value());
  const tlc::StoredFrameKind round = tlc::ros_io::parseDatasetMarker(tlc::ros_io::datasetMarkerText({true, 40}));
  EXPECT_TRUE(round.candidate);
  EXPECT_FALSE(round.skipped);
  EXPECT_EQ(round.frame_index, 40u);
  const tlc::StoredFrameKind skipped =
      tlc::ros_io::parseDatasetMarker(tlc::ros_io::datasetMarkerText({true, 41, true}));
  EXPECT_TRUE(skipped.skipped);
  EXPECT_EQ(skipped.frame_index, 41u);
  std::filesystem::remove_all(dir);
}

// kill -9 at random moments while pairs are appended: every pair whose write() returned (reported
// through a pipe) is in the bag afterwards, and the bag is continued by the next writer. Each
// trial kills after 0-3 acknowledged pairs, at a random moment of the append that follows: the
// count comes from the writer, so a slow machine runs the same trials (kills after a fixed time
// once caught writers that had hardly started: 13 pairs in 30 trials).
TEST(DatasetBagWriter, AKillAtAnyMomentKeepsEveryWrittenPair) {
  const std::string dir = tlc::test_support::tempDir("tlc_dataset_kill_");
  const std::string path = dir + "/dataset.bag";
  std::mt19937 rng(12);
  const std::vector<PairMessages> pairs = {makePair(100.0, 1), makePair(100.0, 2)};
  constexpr int kTrials = 30;
  int acknowledged = 0, journals = 0;
  for (int trial = 0; trial < kTrials; ++trial) {
    const AckingChild child = forkAckingChild([&](const std::function<void()>& ack) {
      DatasetBagWriter writer(path, true);
      for (int i = 0;; ++i) {
        PairMessages m = pairs[i % 2];
        m.image.header.stamp = ros::Time(100.0 + trial * 1000 + i);
        write(writer, m);
        ack();
      }
    });
    const int wanted = static_cast<int>(rng() % 4);
    const int before_kill = readAcks(child.acks_fd, wanted, 120.0);
    // Where the kill lands in the next appends (a pair takes a few ms): the moment is random,
    // no outcome depends on how far the writer got.
    std::this_thread::sleep_for(std::chrono::microseconds(rng() % 20000));
    ::kill(child.pid, SIGKILL);
    int status = 0;
    ::waitpid(child.pid, &status, 0);
    ASSERT_EQ(before_kill, wanted) << "trial " << trial << ": the writer acknowledged no pair for 120 s";
    acknowledged += before_kill + countAcks(child.acks_fd);
    if (acknowledged == 0 && !std::filesystem::exists(path)) continue;  // killed before the first
    journals += std::filesystem::exists(path + ".journal") ? 1 : 0;  // killed inside an append
    const auto contents = tlc::ros_io::readDatasetBag(path);  // recovers from the journal
    EXPECT_TRUE(contents.errors.empty());
    const int in_bag = static_cast<int>(contents.frames.size());
    EXPECT_GE(in_bag, acknowledged) << "trial " << trial << ": a written pair was lost";
    EXPECT_LE(in_bag, acknowledged + 1) << "trial " << trial;
    acknowledged = in_bag;  // a pair in the bag but not acknowledged counts from now on
  }
  std::printf("%d pairs written in %d kills, %d of them inside an append (recovered from the "
              "journal)\n", acknowledged, kTrials, journals);
  EXPECT_EQ(connectionsIn(path), 5u);
}

// A process that dies inside an append, after the journal is written and while the bag is half
// overwritten (SIGXFSZ at a file size limit ends it there, every time): the next reader restores
// the bag from the journal with every pair written before.
TEST(DatasetBagWriter, ADeathInsideAnAppendIsUndoneFromTheJournal) {
  const std::string dir = tlc::test_support::tempDir("tlc_dataset_death_");
  const std::string path = dir + "/dataset.bag";
  const AckingChild child = forkAckingChild([&](const std::function<void()>& ack) {
    const rlimit limit{3u << 20, 3u << 20};  // SIGXFSZ keeps its default action: the end
    ::setrlimit(RLIMIT_FSIZE, &limit);
    DatasetBagWriter writer(path, false);
    for (int i = 0; i < 100; ++i) {
      write(writer, makePair(100.0 + i, i % 3));
      ack();
    }
  });
  int status = 0;
  ::waitpid(child.pid, &status, 0);
  const int acknowledged = countAcks(child.acks_fd);
  ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGXFSZ) << "the writer was not killed";
  ASSERT_GE(acknowledged, 1);
  ASSERT_TRUE(std::filesystem::exists(path + ".journal")) << "not killed inside an append";
  const auto contents = tlc::ros_io::readDatasetBag(path);
  EXPECT_EQ(static_cast<int>(contents.frames.size()), acknowledged);
  EXPECT_TRUE(contents.errors.empty());
  EXPECT_FALSE(std::filesystem::exists(path + ".journal"));
  DatasetBagWriter resumed(path, true);
  write(resumed, makePair(500.0, 1));
  EXPECT_EQ(tlc::ros_io::countDatasetBag(path).pairs, static_cast<std::size_t>(acknowledged) + 1);
}
