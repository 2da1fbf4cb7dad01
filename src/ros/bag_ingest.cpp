// Bag -> FrameSynchronizer -> DatasetBuilder, with every bag fault turned into one line.

#include "thermal_lidar_calibration/ros/bag_ingest.hpp"

#include "thermal_lidar_calibration/app/runtime/bad_frame_reporter.hpp"

#include "thermal_lidar_calibration/ros/bag_message_reader.hpp"
#include "thermal_lidar_calibration/ros/frame_synchronizer.hpp"
#include "thermal_lidar_calibration/ros/msg_conversion.hpp"

#include <rosbag/exceptions.h>
#include <rosbag/view.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>

#include <sys/stat.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace thermal_lidar_calibration {
namespace ros_io {
namespace {

constexpr std::size_t kMaxDistinctWarnings = 5;

const BagTopicInfo* findTopic(const std::vector<BagTopicInfo>& topics, const std::string& name) {
  for (const auto& t : topics) {
    if (t.topic == name) return &t;
  }
  return nullptr;
}

bool startsLikeABag(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char head[13] = {};
  in.read(head, sizeof(head));
  return in.gcount() == sizeof(head) && std::string(head, sizeof(head)) == "#ROSBAG V2.0\n";
}

}  // namespace

void openBag(rosbag::Bag& bag, const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    throw std::invalid_argument("cannot open bag " + path + ": no such file; check --bag");
  }
  if (S_ISDIR(st.st_mode)) {
    throw std::invalid_argument("cannot open bag " + path + ": it is a directory; pass a .bag file");
  }
  try {
    bag.open(path, rosbag::bagmode::Read);
  } catch (const rosbag::BagUnindexedException&) {
    throw std::invalid_argument("bag " + path + " is unindexed (recording was cut short); run "
                                "'rosbag reindex " + path + "' first");
  } catch (const std::exception& e) {
    if (startsLikeABag(path)) {
      throw std::invalid_argument("bag " + path + " is damaged or truncated (" +
                                  std::string(e.what()) + "); try 'rosbag reindex " + path +
                                  "' or record it again");
    }
    throw std::invalid_argument("cannot read " + path + " as a ROS 1 bag (" +
                                std::string(e.what()) + "); is it a .bag file from rosbag record?");
  }
}

std::vector<BagTopicInfo> listBagTopics(rosbag::Bag& bag) {
  std::vector<BagTopicInfo> topics;
  rosbag::View all(bag);
  for (const rosbag::ConnectionInfo* c : all.getConnections()) {
    if (findTopic(topics, c->topic)) continue;
    BagTopicInfo info;
    info.topic = c->topic;
    info.datatype = c->datatype;
    topics.push_back(info);
  }
  for (auto& t : topics) {
    rosbag::View view(bag, rosbag::TopicQuery(t.topic));
    t.messages = view.size();
  }
  std::sort(topics.begin(), topics.end(),
            [](const BagTopicInfo& a, const BagTopicInfo& b) { return a.topic < b.topic; });
  return topics;
}

std::string describeBagTopics(const std::vector<BagTopicInfo>& topics) {
  if (topics.empty()) return "none";
  std::string out;
  for (const auto& t : topics) {
    out += (out.empty() ? "" : ", ") + t.topic + " (" + t.datatype + ", " +
           std::to_string(t.messages) + ")";
  }
  return out;
}

void checkBagTopics(const std::vector<BagTopicInfo>& topics, const BagTopics& wanted,
                    const std::string& bag_path) {
  std::uint64_t total = 0;
  for (const auto& t : topics) total += t.messages;
  if (total == 0) {
    throw std::invalid_argument("bag " + bag_path + " is empty (no messages); record " +
                                wanted.image + ", " + wanted.mask + ", " + wanted.clusters +
                                " and " + wanted.camera_info);
  }
  struct Required {
    const std::string& topic;
    const char* type;
    const char* flag;
  };
  std::vector<Required> required = {{wanted.image, "sensor_msgs/Image", "--image-topic"}};
  if (wanted.detect) {
    required.push_back({wanted.points, "sensor_msgs/PointCloud2", "--points-topic"});
  } else {
    required.push_back({wanted.mask, "sensor_msgs/Image", "--mask-topic"});
    required.push_back({wanted.clusters, "sensor_msgs/PointCloud2", "--clusters-topic"});
    // Raw sensor data only: the person detectors make the mask and clusters.
    const BagTopicInfo* points = findTopic(topics, wanted.points);
    const bool has_people = findTopic(topics, wanted.mask) || findTopic(topics, wanted.clusters);
    if (points && points->messages > 0 && !has_people) {
      throw std::invalid_argument(
          "bag " + bag_path + " has raw " + wanted.points + " but no " + wanted.mask + " or " +
          wanted.clusters + ": pass --detect to find the people with the built-in detectors " +
          "(or --mask-topic / --clusters-topic if your own detectors' topics have other names)");
    }
  }
  for (const auto& r : required) {
    const BagTopicInfo* info = findTopic(topics, r.topic);
    if (!info || info->messages == 0) {
      throw std::invalid_argument("topic " + r.topic + " is not in bag " + bag_path +
                                  " (bag topics: " + describeBagTopics(topics) + "); pass " +
                                  r.flag + " TOPIC");
    }
    if (info->datatype != r.type) {
      throw std::invalid_argument("topic " + r.topic + " in bag " + bag_path + " has type " +
                                  info->datatype + ", expected " + r.type + "; pass " + r.flag +
                                  " TOPIC with the right topic");
    }
  }
}

CameraModel cameraModelFromBag(rosbag::Bag& bag, const std::string& topic,
                               const std::vector<BagTopicInfo>& topics) {
  const BagTopicInfo* info = findTopic(topics, topic);
  if (!info || info->messages == 0) {
    throw std::invalid_argument("no CameraInfo on " + topic +
                                " in the bag; pass --camera-info FILE.yaml (camera_calibration "
                                "format) or --camera-info-topic TOPIC");
  }
  if (info->datatype != "sensor_msgs/CameraInfo") {
    throw std::invalid_argument("topic " + topic + " has type " + info->datatype +
                                ", expected sensor_msgs/CameraInfo; pass --camera-info FILE.yaml");
  }
  try {
    rosbag::View view(bag, rosbag::TopicQuery(topic));
    for (const rosbag::MessageInstance& m : view) {
      const sensor_msgs::CameraInfo::ConstPtr msg = m.instantiate<sensor_msgs::CameraInfo>();
      if (msg) return cameraModelFromMsg(*msg);
    }
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(topic + ": " + e.what() + " (or pass --camera-info FILE.yaml)");
  } catch (const std::exception& e) {
    throw std::invalid_argument("cannot read CameraInfo on " + topic + " (" + e.what() +
                                "); pass --camera-info FILE.yaml");
  }
  throw std::invalid_argument("no readable CameraInfo on " + topic +
                              " in the bag; pass --camera-info FILE.yaml");
}

namespace {

// One bag through the synchronizer into the builder: what ingestBag does, message by message.
class BagReader {
 public:
  BagReader(const BagTopics& topics, const CoreParameters& params, DatasetBuilder& builder,
            const IngestCallbacks& callbacks, PersonDetectionAdapter* detectors)
      : topics_(topics),
        builder_(builder),
        callbacks_(callbacks),
        detectors_(detectors),
        time_field_(PointTimeField::parse(params.point_time_field)),
        sync_(params.sync_queue_size, params.sync_slop_s,
              [this](const sensor_msgs::Image::ConstPtr& image, const sensor_msgs::Image::ConstPtr& mask,
                     const sensor_msgs::PointCloud2::ConstPtr& clusters) { onFrame(image, mask, clusters); }) {}

  BagIngestStats read(rosbag::Bag& bag) {
    std::vector<std::string> wanted = {topics_.image, topics_.mask, topics_.clusters};
    if (topics_.detect) wanted = {topics_.image, topics_.points};
    try {
      BagMessageReader reader(bag, wanted, {topics_.clusters, topics_.points});
      stats_.messages_total = reader.size();
      BagMessage m;
      while (reader.next(m)) {
        ++stats_.messages_read;
        add(m);
        if (callbacks_.progress && !callbacks_.progress(stats_, builder_)) {
          stats_.interrupted = true;
          break;
        }
      }
      const std::string damage = reader.damage();
      if (!damage.empty()) describeDamage(damage);
    } catch (const std::exception& e) {
      describeDamage(e.what());
    }
    if (!stats_.interrupted) {
      sync_.flush();             // the last frame of the bag counts too
      builder_.flushPending();  // and the pairs waiting for scans that will not come
    }
    return stats_;
  }

 private:
  void describeDamage(const std::string& what) {
    stats_.damage = "the bag could not be read past message " + std::to_string(stats_.messages_read) + " (" +
                    what + ")";
  }

  void add(const BagMessage& m) {
    if (!m.undecodable.empty()) {
      // One message could not be deserialised (truncated record): skip it.
      ++stats_.undecodable_messages;
      if (stats_.undecodable_messages == 1 && callbacks_.warn) {
        callbacks_.warn("cannot deserialise a message on " + m.topic + " (" + m.undecodable +
                        "); skipping such messages");
      }
      return;
    }
    if (topics_.detect) {
      addDetected(m);
    } else if (m.topic == topics_.clusters) {
      if (m.cloud) observe(*m.cloud, m.topic);
      note(m.topic, sync_.addClusters(m.cloud));
    } else if (m.topic == topics_.image) {
      note(m.topic, sync_.addImage(m.image));
    } else {
      note(m.topic, sync_.addMask(m.image));
    }
  }

  // --detect: the detectors make each raw message into what a mask / clusters topic would carry;
  // a message they cannot read is a bad frame like any other.
  void addDetected(const BagMessage& m) {
    try {
      if (m.topic == topics_.points) {
        if (!m.cloud) return;
        const sensor_msgs::PointCloud2::ConstPtr clusters = detectors_->detect(*m.cloud, m.topic).clusters;
        if (clusters) observe(*clusters, topics_.clusters);
        note(m.topic, sync_.addClusters(clusters));
      } else {
        if (!m.image) return;
        const SegmentedImage seg = detectors_->segment(m.image, m.topic);
        note(m.topic, sync_.addImage(seg.image));
        note(topics_.mask, sync_.addMask(seg.mask));
      }
    } catch (const std::invalid_argument& e) {
      reportBad(m.time_s, e.what());
    }
  }

  void onFrame(const sensor_msgs::Image::ConstPtr& image, const sensor_msgs::Image::ConstPtr& mask,
               const sensor_msgs::PointCloud2::ConstPtr& clusters) {
    ++stats_.frames;
    const OfferOutcome outcome = builder_.offer([&] {
      return decodeFrame(*image, *mask, *clusters, topics_.image, topics_.mask, topics_.clusters, time_field_);
    });
    if (outcome.decision != GateDecision::kBadMessage) return;
    reportBad(image->header.stamp.toSec(), outcome.error.empty() ? "undecodable frame" : outcome.error);
  }

  // Every clusters message, kept frame or not, is a scan the people's motion is measured from
  // (issue 21). One that cannot be decoded is reported when its frame is.
  void observe(const sensor_msgs::PointCloud2& clusters, const std::string& topic) {
    if (!builder_.tracksMotion()) return;
    try {
      builder_.observeScan(decodeScanPeople(clusters, topic, time_field_));
    } catch (const std::invalid_argument&) {
    }
  }

  // The node's account and wording (BadFrameReporter), in the bag's own time: one line per kind
  // of fault and 5 s of data, counting the rest; every error also counted for the summary.
  void reportBad(double stamp_s, const std::string& error) {
    ++stats_.bad_message_errors[error];
    const std::string line = reporter_.reportAtStamp(stamp_s, "", error);
    if (!line.empty() && callbacks_.warn) callbacks_.warn(line);
  }

  // Messages whose stamps ApproximateTime cannot handle are refused by the synchronizer: say so
  // for the first few.
  void note(const std::string& topic, const FrameSynchronizer::AddOutcome& outcome) {
    if (outcome.fault.empty() || ++stamp_faults_ > kMaxDistinctWarnings || !callbacks_.warn) return;
    callbacks_.warn(topic + ": " + outcome.fault +
                    (stamp_faults_ == kMaxDistinctWarnings ? " (further ones not shown)" : ""));
  }

  const BagTopics& topics_;
  DatasetBuilder& builder_;
  const IngestCallbacks& callbacks_;
  PersonDetectionAdapter* detectors_;
  const PointTimeField time_field_;
  BagIngestStats stats_;
  BadFrameReporter reporter_;
  std::uint64_t stamp_faults_ = 0;
  FrameSynchronizer sync_;
};

}  // namespace

BagIngestStats ingestBag(rosbag::Bag& bag, const BagTopics& topics, const CoreParameters& params,
                         DatasetBuilder& builder, const IngestCallbacks& callbacks,
                         PersonDetectionAdapter* detectors) {
  if (topics.detect && !detectors) throw std::logic_error("ingestBag: detect without detectors");
  return BagReader(topics, params, builder, callbacks, detectors).read(bag);
}

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
