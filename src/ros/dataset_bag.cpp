// Dataset bag: kept pairs appended through BagAppender, and read back for ~resume.

#include "thermal_lidar_calibration/ros/dataset_bag.hpp"

#include "thermal_lidar_calibration/ros/msg_conversion.hpp"

#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <std_msgs/String.h>

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <map>
#include <stdexcept>

namespace thermal_lidar_calibration {
namespace ros_io {
namespace {

bool fileExists(const std::string& path) { return ::access(path.c_str(), F_OK) == 0; }

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw std::runtime_error("dataset bag " + path + ": " + what);
}

constexpr const char* kPairText = "pair kept by calibration_node (already gated)";
constexpr const char* kCandidateText = "association candidate held by calibration_node";
constexpr const char* kSkippedText = "skipped frame held by calibration_node for the final round";
constexpr const char* kFrameText = "; frame ";

// One pair as one chunk: all five messages stamped with the image's time.
std::vector<BagAppender::Message> pairMessages(const sensor_msgs::Image& image,
                                               const sensor_msgs::Image& mask,
                                               const sensor_msgs::PointCloud2& clusters,
                                               const sensor_msgs::CameraInfo& camera_info,
                                               const StoredFrameKind& kind) {
  const ros::Time time = image.header.stamp < ros::TIME_MIN ? ros::TIME_MIN : image.header.stamp;
  sensor_msgs::CameraInfo info = camera_info;
  info.header.stamp = image.header.stamp;
  if (info.header.frame_id.empty()) info.header.frame_id = image.header.frame_id;
  std_msgs::String marker;
  marker.data = datasetMarkerText(kind);
  return {BagAppender::message(DatasetBagTopics::kCameraInfo, time, info),
          BagAppender::message(DatasetBagTopics::kImage, time, image),
          BagAppender::message(DatasetBagTopics::kMask, time, mask),
          BagAppender::message(DatasetBagTopics::kClusters, time, clusters),
          BagAppender::message(kind.skipped     ? DatasetBagTopics::kSkippedMarker
                               : kind.candidate ? DatasetBagTopics::kCandidateMarker
                                                : DatasetBagTopics::kMarker,
                               time, marker)};
}

}  // namespace

std::string datasetMarkerText(const StoredFrameKind& kind) {
  std::string text = kind.skipped ? kSkippedText : kind.candidate ? kCandidateText : kPairText;
  if (kind.frame_index) text += kFrameText + std::to_string(*kind.frame_index);
  return text;
}

StoredFrameKind parseDatasetMarker(const std::string& text) {
  StoredFrameKind kind;
  kind.skipped = text.rfind(kSkippedText, 0) == 0;
  kind.candidate = kind.skipped || text.rfind(kCandidateText, 0) == 0;
  const std::size_t at = text.rfind(kFrameText);
  if (at != std::string::npos) {
    const std::string digits = text.substr(at + std::strlen(kFrameText));
    if (!digits.empty() && digits.find_first_not_of("0123456789") == std::string::npos && digits.size() < 20) {
      kind.frame_index = std::stoull(digits);
    }
  }
  return kind;
}

DatasetBagWriter::DatasetBagWriter(std::string path, bool append) : path_(std::move(path)) {
  if (path_.empty()) throw std::invalid_argument("dataset bag path is empty");
  if (fileExists(path_) && !append) {
    const std::string previous = path_ + ".previous";
    if (std::rename(path_.c_str(), previous.c_str()) != 0) {
      fail(path_, std::string("cannot move the old bag to ") + previous + ": " +
                      std::strerror(errno));
    }
  }
  appender_ = std::make_unique<BagAppender>(path_);
}

DatasetBagWriter::~DatasetBagWriter() = default;

void DatasetBagWriter::write(const sensor_msgs::Image& image, const sensor_msgs::Image& mask,
                             const sensor_msgs::PointCloud2& clusters,
                             const sensor_msgs::CameraInfo& camera_info, const StoredFrameKind& kind) {
  appender_->append(pairMessages(image, mask, clusters, camera_info, kind));
}

void DatasetBagWriter::clear() {
  for (const std::string& p : {path_, path_ + ".tmp", path_ + ".journal", path_ + ".journal.tmp"}) {
    if (fileExists(p) && std::remove(p.c_str()) != 0) {
      fail(p, std::string("cannot delete: ") + std::strerror(errno));
    }
  }
  appender_ = std::make_unique<BagAppender>(path_);
}

std::size_t DatasetBagWriter::indexBytes() const { return appender_->indexBytes(); }

bool recoverDatasetBag(const std::string& path) { return recoverBagAppend(path); }

DatasetBagContents readDatasetBag(const std::string& path, bool recover) {
  if (recover) recoverDatasetBag(path);
  DatasetBagContents contents;
  rosbag::Bag bag;
  try {
    bag.open(path, rosbag::bagmode::Read);
  } catch (const rosbag::BagException& e) {
    fail(path, e.what());
  }
  const std::vector<std::string> topics = {DatasetBagTopics::kImage,      DatasetBagTopics::kMask,
                                           DatasetBagTopics::kClusters,   DatasetBagTopics::kCameraInfo,
                                           DatasetBagTopics::kMarker,     DatasetBagTopics::kCandidateMarker,
                                           DatasetBagTopics::kSkippedMarker};
  rosbag::View view(bag, rosbag::TopicQuery(topics));
  sensor_msgs::Image::ConstPtr image, mask;
  sensor_msgs::PointCloud2::ConstPtr clusters;
  // A frame's marker shares its time (pairMessages) but may come before or after its other
  // messages: matched by time once all are read.
  std::map<std::uint64_t, std::string> markers;
  std::vector<std::uint64_t> frame_times_ns;
  for (const rosbag::MessageInstance& m : view) {
    const std::string& topic = m.getTopic();
    if (topic == DatasetBagTopics::kMarker || topic == DatasetBagTopics::kCandidateMarker ||
        topic == DatasetBagTopics::kSkippedMarker) {
      if (const auto text = m.instantiate<std_msgs::String>()) markers[m.getTime().toNSec()] = text->data;
      continue;
    }
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
      // The chunk's messages are stamped with the image's time (pairMessages), clamped as there.
      frame_times_ns.push_back((image->header.stamp < ros::TIME_MIN ? ros::TIME_MIN : image->header.stamp).toNSec());
    } catch (const std::invalid_argument& e) {
      contents.errors.push_back(e.what());
    }
    image.reset();
    mask.reset();
    clusters.reset();
  }
  for (const std::uint64_t t : frame_times_ns) {
    const auto marker = markers.find(t);
    contents.kinds.push_back(marker == markers.end() ? StoredFrameKind{} : parseDatasetMarker(marker->second));
  }
  return contents;
}

DatasetBagCounts countDatasetBag(const std::string& path) {
  rosbag::Bag bag;
  try {
    bag.open(path, rosbag::bagmode::Read);  // reads the index only
    DatasetBagCounts counts;
    counts.pairs = rosbag::View(bag, rosbag::TopicQuery(DatasetBagTopics::kMarker)).size();
    counts.candidates = rosbag::View(bag, rosbag::TopicQuery(DatasetBagTopics::kCandidateMarker)).size();
    counts.skipped_frames = rosbag::View(bag, rosbag::TopicQuery(DatasetBagTopics::kSkippedMarker)).size();
    return counts;
  } catch (const rosbag::BagException& e) {
    fail(path, e.what());
  }
}

RestoredDataset restoreDataset(DatasetBagContents contents, DatasetBuilder& builder) {
  RestoredDataset restored;
  restored.skipped = std::move(contents.errors);
  // rosbag reads in stamp order; the session kept its frames in the order they were offered,
  // which a resumed session replaying a drive from its start breaks (its new frames come after
  // the stored ones). The frame numbers give that order back, and with it the pairs' order the
  // session fitted (the bootstrap resamples blocks of consecutive pairs).
  std::vector<std::size_t> order(contents.frames.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  const bool numbered = contents.kinds.size() == contents.frames.size() &&
                        std::all_of(contents.kinds.begin(), contents.kinds.end(),
                                    [](const StoredFrameKind& k) { return k.frame_index.has_value(); });
  restored.numbered = numbered && !order.empty();
  if (numbered) {
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return *contents.kinds[a].frame_index < *contents.kinds[b].frame_index;
    });
  }
  for (const std::size_t i : order) {
    const StoredFrameKind kind = i < contents.kinds.size() ? contents.kinds[i] : StoredFrameKind{};
    const OfferOutcome outcome = builder.restore(std::move(contents.frames[i]), kind);
    if (outcome.decision == GateDecision::kKept) {
      ++restored.pairs;
    } else if (outcome.skipped_held) {
      ++restored.skipped_frames;
    } else if (outcome.candidate) {
      ++restored.candidates;
    } else {
      // A candidate when the builder does not pair by association, or a skipped frame when it
      // runs no final round, is left out on purpose.
      if (outcome.decision == GateDecision::kBadMessage) restored.skipped.push_back(outcome.error);
      continue;
    }
    restored.stamps_ns.push_back(contents.pair_stamps_ns[i]);
  }
  return restored;
}

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
