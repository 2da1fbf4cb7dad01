// Dataset bag: kept pairs appended through BagAppender, and read back for ~resume.

#include "thermal_lidar_calibration/ros/dataset_bag.hpp"

#include "thermal_lidar_calibration/ros/msg_conversion.hpp"

#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <std_msgs/String.h>

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace thermal_lidar_calibration {
namespace ros_io {
namespace {

bool fileExists(const std::string& path) { return ::access(path.c_str(), F_OK) == 0; }

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw std::runtime_error("dataset bag " + path + ": " + what);
}

// One pair as one chunk: all five messages stamped with the image's time.
std::vector<BagAppender::Message> pairMessages(const sensor_msgs::Image& image,
                                               const sensor_msgs::Image& mask,
                                               const sensor_msgs::PointCloud2& clusters,
                                               const sensor_msgs::CameraInfo& camera_info) {
  const ros::Time time = image.header.stamp < ros::TIME_MIN ? ros::TIME_MIN : image.header.stamp;
  sensor_msgs::CameraInfo info = camera_info;
  info.header.stamp = image.header.stamp;
  if (info.header.frame_id.empty()) info.header.frame_id = image.header.frame_id;
  std_msgs::String marker;
  marker.data = "pair kept by calibration_node (already gated)";
  return {BagAppender::message(DatasetBagTopics::kCameraInfo, time, info),
          BagAppender::message(DatasetBagTopics::kImage, time, image),
          BagAppender::message(DatasetBagTopics::kMask, time, mask),
          BagAppender::message(DatasetBagTopics::kClusters, time, clusters),
          BagAppender::message(DatasetBagTopics::kMarker, time, marker)};
}

}  // namespace

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
                             const sensor_msgs::CameraInfo& camera_info) {
  appender_->append(pairMessages(image, mask, clusters, camera_info));
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
