// Dataset bag: crash-safe append of kept pairs, and reading them back for ~resume.

#include "thermal_lidar_calibration/ros/dataset_bag.hpp"

#include "thermal_lidar_calibration/ros/msg_conversion.hpp"

#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <std_msgs/String.h>

#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <memory>
#include <stdexcept>

namespace thermal_lidar_calibration {
namespace ros_io {
namespace {

constexpr char kJournalMagic[4] = {'T', 'L', 'C', 'J'};
constexpr std::size_t kVersionLineLength = 13;  // "#ROSBAG V2.0\n"
constexpr std::size_t kPrefixBytes = 8192;      // covers the 4096-byte file header record

bool fileExists(const std::string& path) { return ::access(path.c_str(), F_OK) == 0; }

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw std::runtime_error("dataset bag " + path + ": " + what);
}

std::string readAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, std::string("cannot read: ") + std::strerror(errno));
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::uint64_t readU64(const char* p) {
  std::uint64_t v = 0;
  for (int i = 7; i >= 0; --i) v = (v << 8) | static_cast<unsigned char>(p[i]);
  return v;
}
std::uint32_t readU32(const char* p) {
  std::uint32_t v = 0;
  for (int i = 3; i >= 0; --i) v = (v << 8) | static_cast<unsigned char>(p[i]);
  return v;
}
void appendU64(std::string& s, std::uint64_t v) {
  for (int i = 0; i < 8; ++i) s.push_back(static_cast<char>((v >> (8 * i)) & 0xff));
}

// index_pos from the rosbag 2.0 file header record (the offset at which append truncates).
std::uint64_t indexPosition(const std::string& path, const std::string& bytes,
                            std::uint64_t file_size) {
  if (bytes.size() < kVersionLineLength + 4 || bytes.compare(0, 13, "#ROSBAG V2.0\n") != 0) {
    fail(path, "not a ROS 1 (v2.0) bag");
  }
  const std::uint32_t header_len = readU32(bytes.data() + kVersionLineLength);
  std::size_t pos = kVersionLineLength + 4;
  const std::size_t end = pos + header_len;
  if (end > bytes.size()) fail(path, "truncated file header");
  while (pos + 4 <= end) {
    const std::uint32_t field_len = readU32(bytes.data() + pos);
    pos += 4;
    if (pos + field_len > end) break;
    const std::string field = bytes.substr(pos, field_len);
    if (field.compare(0, 10, "index_pos=") == 0 && field.size() == 18) {
      const std::uint64_t index_pos = readU64(field.data() + 10);
      if (index_pos == 0 || index_pos > file_size) {
        fail(path, "the bag is not indexed (interrupted without a journal); run "
                   "'rosbag reindex " + path + "' and try again");
      }
      return index_pos;
    }
    pos += field_len;
  }
  fail(path, "no index_pos in the file header");
}

void writeMessages(rosbag::Bag& bag, const sensor_msgs::Image& image,
                   const sensor_msgs::Image& mask, const sensor_msgs::PointCloud2& clusters,
                   const sensor_msgs::CameraInfo& camera_info) {
  const ros::Time time = image.header.stamp < ros::TIME_MIN ? ros::TIME_MIN : image.header.stamp;
  sensor_msgs::CameraInfo info = camera_info;
  info.header.stamp = image.header.stamp;
  if (info.header.frame_id.empty()) info.header.frame_id = image.header.frame_id;
  bag.write(DatasetBagTopics::kCameraInfo, time, info);
  bag.write(DatasetBagTopics::kImage, time, image);
  bag.write(DatasetBagTopics::kMask, time, mask);
  bag.write(DatasetBagTopics::kClusters, time, clusters);
  std_msgs::String marker;
  marker.data = "pair kept by calibration_node (already gated)";
  bag.write(DatasetBagTopics::kMarker, time, marker);
}

// Opens `path` in `mode`, writes one pair and closes. rosbag::Bag's destructor writes the index
// of a bag still open; on a full disk that write throws again, and a throwing destructor ends the
// process (std::terminate). So the bag is closed explicitly, and after a failure the object is
// abandoned instead of destroyed: a small leak per failed write, and the node stops recording
// after the first.
void writePairToBag(const std::string& path, rosbag::bagmode::BagMode mode,
                    const sensor_msgs::Image& image, const sensor_msgs::Image& mask,
                    const sensor_msgs::PointCloud2& clusters,
                    const sensor_msgs::CameraInfo& camera_info) {
  auto bag = std::make_unique<rosbag::Bag>();
  try {
    bag->open(path, mode);
    bag->setCompression(rosbag::compression::LZ4);
    writeMessages(*bag, image, mask, clusters, camera_info);
    bag->close();
  } catch (...) {
    static_cast<void>(bag.release());
    throw;
  }
}

}  // namespace

DatasetBagWriter::DatasetBagWriter(std::string path, bool append) : path_(std::move(path)) {
  if (path_.empty()) throw std::invalid_argument("dataset bag path is empty");
  exists_ = fileExists(path_);
  if (exists_ && !append) {
    const std::string previous = path_ + ".previous";
    if (std::rename(path_.c_str(), previous.c_str()) != 0) {
      fail(path_, std::string("cannot move the old bag to ") + previous + ": " +
                      std::strerror(errno));
    }
    exists_ = false;
  }
}

void DatasetBagWriter::write(const sensor_msgs::Image& image, const sensor_msgs::Image& mask,
                             const sensor_msgs::PointCloud2& clusters,
                             const sensor_msgs::CameraInfo& camera_info) {
  if (exists_) {
    appendWithJournal(image, mask, clusters, camera_info);
    return;
  }
  const std::string tmp = path_ + ".tmp";
  try {
    writePairToBag(tmp, rosbag::bagmode::Write, image, mask, clusters, camera_info);
  } catch (const std::exception& e) {
    std::remove(tmp.c_str());
    fail(path_, std::string("cannot write ") + tmp + ": " + e.what());
  }
  if (std::rename(tmp.c_str(), path_.c_str()) != 0) {
    const int error = errno;
    std::remove(tmp.c_str());
    fail(path_, std::string("cannot rename ") + tmp + ": " + std::strerror(error));
  }
  exists_ = true;
}

void DatasetBagWriter::appendWithJournal(const sensor_msgs::Image& image,
                                         const sensor_msgs::Image& mask,
                                         const sensor_msgs::PointCloud2& clusters,
                                         const sensor_msgs::CameraInfo& camera_info) {
  // The journal holds what rosbag's append overwrites: the header and everything from index_pos.
  std::string journal;
  {
    std::ifstream in(path_, std::ios::binary | std::ios::ate);
    if (!in) fail(path_, std::string("cannot open: ") + std::strerror(errno));
    const std::uint64_t size = static_cast<std::uint64_t>(in.tellg());
    std::string prefix(static_cast<std::size_t>(std::min<std::uint64_t>(size, kPrefixBytes)), '\0');
    in.seekg(0);
    in.read(&prefix[0], static_cast<std::streamsize>(prefix.size()));
    // Read the whole header record if it is longer than the prefix (it never is for rosbag).
    const std::uint64_t index_pos = indexPosition(path_, prefix, size);
    std::string tail(static_cast<std::size_t>(size - index_pos), '\0');
    in.seekg(static_cast<std::streamoff>(index_pos));
    in.read(&tail[0], static_cast<std::streamsize>(tail.size()));
    if (!in) fail(path_, "cannot read the index for the journal");
    journal.append(kJournalMagic, 4);
    appendU64(journal, size);
    appendU64(journal, index_pos);
    appendU64(journal, prefix.size());
    journal += prefix;
    journal += tail;
  }
  const std::string journal_path = path_ + ".journal";
  const std::string journal_tmp = journal_path + ".tmp";
  {
    std::ofstream out(journal_tmp, std::ios::binary | std::ios::trunc);
    out.write(journal.data(), static_cast<std::streamsize>(journal.size()));
    out.close();
    if (!out) {
      std::remove(journal_tmp.c_str());
      fail(path_, "cannot write the journal " + journal_tmp + " (disk full?)");
    }
  }
  if (std::rename(journal_tmp.c_str(), journal_path.c_str()) != 0) {
    fail(path_, "cannot rename the journal: " + std::string(std::strerror(errno)));
  }
  try {
    writePairToBag(path_, rosbag::bagmode::Append, image, mask, clusters, camera_info);
  } catch (const std::exception& e) {
    // Put the bag back as it was before this append (every earlier pair readable).
    std::string restored = "the bag was restored to its earlier pairs";
    try {
      recoverDatasetBag(path_);
    } catch (const std::exception& r) {
      restored = std::string("restoring it failed too (") + r.what() +
                 "); the journal is kept, start with ~resume to restore it";
    }
    fail(path_, std::string("cannot append: ") + e.what() + "; " + restored);
  }
  std::remove(journal_path.c_str());
}

void DatasetBagWriter::clear() {
  for (const std::string& p : {path_, path_ + ".tmp", path_ + ".journal", path_ + ".journal.tmp"}) {
    if (fileExists(p) && std::remove(p.c_str()) != 0) {
      fail(p, std::string("cannot delete: ") + std::strerror(errno));
    }
  }
  exists_ = false;
}

bool recoverDatasetBag(const std::string& path) {
  std::remove((path + ".journal.tmp").c_str());
  std::remove((path + ".tmp").c_str());
  const std::string journal_path = path + ".journal";
  if (!fileExists(journal_path)) return false;
  const std::string journal = readAll(journal_path);
  if (journal.size() < 28 || journal.compare(0, 4, kJournalMagic, 4) != 0) {
    fail(path, "journal " + journal_path + " is damaged; delete it and run 'rosbag reindex'");
  }
  const std::uint64_t size = readU64(journal.data() + 4);
  const std::uint64_t index_pos = readU64(journal.data() + 12);
  const std::uint64_t prefix_len = readU64(journal.data() + 20);
  if (28 + prefix_len + (size - index_pos) != journal.size() || index_pos > size) {
    fail(path, "journal " + journal_path + " is damaged; delete it and run 'rosbag reindex'");
  }
  std::FILE* f = std::fopen(path.c_str(), "r+b");
  if (!f) fail(path, std::string("cannot open for recovery: ") + std::strerror(errno));
  bool ok = std::fwrite(journal.data() + 28, 1, prefix_len, f) == prefix_len;
  ok = ok && std::fseek(f, static_cast<long>(index_pos), SEEK_SET) == 0;
  const std::size_t tail_len = static_cast<std::size_t>(size - index_pos);
  ok = ok && std::fwrite(journal.data() + 28 + prefix_len, 1, tail_len, f) == tail_len;
  ok = ok && std::fflush(f) == 0 && ::ftruncate(::fileno(f), static_cast<off_t>(size)) == 0;
  ok = (std::fclose(f) == 0) && ok;
  if (!ok) fail(path, "recovery from the journal failed: " + std::string(std::strerror(errno)));
  std::remove(journal_path.c_str());
  return true;
}

DatasetBagContents readDatasetBag(const std::string& path) {
  recoverDatasetBag(path);
  DatasetBagContents contents;
  rosbag::Bag bag;
  try {
    bag.open(path, rosbag::bagmode::Read);
  } catch (const rosbag::BagException& e) {
    fail(path, e.what());
  }
  const std::vector<std::string> topics = {DatasetBagTopics::kImage, DatasetBagTopics::kMask,
                                           DatasetBagTopics::kClusters,
                                           DatasetBagTopics::kCameraInfo};
  rosbag::View view(bag, rosbag::TopicQuery(topics));
  sensor_msgs::Image::ConstPtr image, mask;
  sensor_msgs::PointCloud2::ConstPtr clusters;
  for (const rosbag::MessageInstance& m : view) {
    const std::string& topic = m.getTopic();
    if (topic == DatasetBagTopics::kImage) {
      image = m.instantiate<sensor_msgs::Image>();
    } else if (topic == DatasetBagTopics::kMask) {
      mask = m.instantiate<sensor_msgs::Image>();
    } else if (topic == DatasetBagTopics::kClusters) {
      clusters = m.instantiate<sensor_msgs::PointCloud2>();
    } else if (const auto info = m.instantiate<sensor_msgs::CameraInfo>()) {
      try {
        contents.camera = cameraModelFromMsg(*info);
      } catch (const std::invalid_argument& e) {
        contents.errors.push_back(e.what());
      }
    }
    if (!image || !mask || !clusters) continue;
    try {
      Frame frame = decodeFrame(*image, *mask, *clusters, DatasetBagTopics::kImage,
                                DatasetBagTopics::kMask, DatasetBagTopics::kClusters);
      contents.camera_frame = frame.camera_frame;
      contents.lidar_frame = frame.lidar_frame;
      contents.frames.push_back(std::move(frame));
      contents.pair_stamps_ns.push_back(image->header.stamp.toNSec());
    } catch (const std::invalid_argument& e) {
      contents.errors.push_back(e.what());
    }
    image.reset();
    mask.reset();
    clusters.reset();
  }
  return contents;
}

std::size_t countDatasetBagPairs(const std::string& path) {
  rosbag::Bag bag;
  try {
    bag.open(path, rosbag::bagmode::Read);  // reads the index only
    return rosbag::View(bag, rosbag::TopicQuery(DatasetBagTopics::kMarker)).size();
  } catch (const rosbag::BagException& e) {
    fail(path, e.what());
  }
}

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
