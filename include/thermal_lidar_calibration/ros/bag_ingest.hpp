#pragma once
// Reading a ROS 1 bag into the shared ingest path: topics checked up front, intrinsics from the
// bag or a file, messages fed to FrameSynchronizer, each matched triple offered to the core's
// DatasetBuilder with ros_io::decodeFrame (exactly what calibration_node does with topics).

#include "thermal_lidar_calibration/core/camera_model.hpp"
#include "thermal_lidar_calibration/core/dataset_builder.hpp"
#include "thermal_lidar_calibration/app/parameters/core_parameters.hpp"
#include "thermal_lidar_calibration/ros/person_detection_adapter.hpp"

#include <rosbag/bag.h>

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace thermal_lidar_calibration {
namespace ros_io {

struct BagTopics {
  std::string image, mask, clusters, camera_info;
  std::string points;   // the raw cloud, read instead of mask and clusters when detecting
  bool detect = false;  // run the person detectors on image and points (calibrate_bag --detect)
};

struct BagTopicInfo {
  std::string topic;
  std::string datatype;
  std::uint32_t messages = 0;
};

struct BagIngestStats {
  std::uint64_t messages_read = 0;  // image + mask + clusters messages fed to the synchronizer
  std::uint64_t messages_total = 0; // of those three topics in the bag
  std::uint64_t undecodable_messages = 0;  // could not be deserialised at all
  std::uint64_t frames = 0;         // synchronized triples offered to the DatasetBuilder
  std::map<std::string, std::uint64_t> bad_message_errors;  // distinct decode error -> count
  std::string damage;               // why reading stopped early, if it did
  bool interrupted = false;
};

// Opens for reading. Throws std::invalid_argument: missing file, not a bag, unindexed bag.
void openBag(rosbag::Bag& bag, const std::string& path);
std::vector<BagTopicInfo> listBagTopics(rosbag::Bag& bag);
// "/a (sensor_msgs/Image, 12), /b (...)" or "none".
std::string describeBagTopics(const std::vector<BagTopicInfo>& topics);
// Throws std::invalid_argument if the bag is empty or a topic is missing or of the wrong type
// (image, mask and clusters; with `detect`, image and points). A bag with raw topics but no
// mask/cluster topics, read without `detect`, is refused with an error that names --detect.
void checkBagTopics(const std::vector<BagTopicInfo>& topics, const BagTopics& wanted,
                    const std::string& bag_path);
// First CameraInfo on `topic`; throws std::invalid_argument (saying to pass --camera-info).
CameraModel cameraModelFromBag(rosbag::Bag& bag, const std::string& topic,
                               const std::vector<BagTopicInfo>& topics);

struct IngestCallbacks {
  // After every message; return false to stop reading (Ctrl-C).
  std::function<bool(const BagIngestStats&, const DatasetBuilder&)> progress;
  // The first time each distinct per-frame decode error is seen (at most a few).
  std::function<void(const std::string&)> warn;
};

// Feeds the bag's image, mask and clusters messages, in bag order, through FrameSynchronizer
// into `builder`. With topics.detect, `detectors` turns each image into (image, mask) and each
// raw cloud into clusters first, and those go the same way. A damaged tail ends the read with a
// note in `damage`, not an exception.
BagIngestStats ingestBag(rosbag::Bag& bag, const BagTopics& topics, const CoreParameters& params,
                         DatasetBuilder& builder, const IngestCallbacks& callbacks,
                         PersonDetectionAdapter* detectors = nullptr);

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
