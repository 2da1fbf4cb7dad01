#pragma once
// The node's dataset on disk: every kept pair (and, pairing by association, every frame held as
// a candidate for it) is appended to a ROS 1 bag as soon as it is kept,
// laid out with the INTERFACE topics (/thermal/image_raw, /thermal/human_mask,
// /lidar/human_clusters, /thermal/camera_info) so calibrate_bag can re-run on it. The original
// messages are stored (not the binarised masks), so a re-run decodes exactly what the node saw.
//
// Each pair is one chunk appended by BagAppender: an append costs the same at pair 500 as at pair 5,
// and a kill at any moment leaves a readable bag with every pair whose write() returned (see
// bag_appender.hpp for how).

#include "thermal_lidar_calibration/core/calibration_pair.hpp"
#include "thermal_lidar_calibration/core/camera_model.hpp"
#include "thermal_lidar_calibration/core/dataset_builder.hpp"
#include "thermal_lidar_calibration/ros/bag_appender.hpp"

#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace thermal_lidar_calibration {
namespace ros_io {

// Topic names inside a dataset bag (the INTERFACE defaults with a leading '/').
struct DatasetBagTopics {
  static constexpr const char* kImage = "/thermal/image_raw";
  static constexpr const char* kMask = "/thermal/human_mask";
  static constexpr const char* kClusters = "/lidar/human_clusters";
  static constexpr const char* kCameraInfo = "/thermal/camera_info";
  // std_msgs/String written with each pair: tells calibrate_bag that these frames were already
  // gated by the node, so it must not apply the skip rule a second time. Its text says the
  // frame's place among those offered (StoredFrameKind): "pair kept by calibration_node (already
  // gated); frame 120".
  static constexpr const char* kMarker = "/thermal_lidar_calibration/dataset_pair";
  // The same for a frame held as an association candidate, on a topic of its own so that the
  // bag's index alone counts the pairs: "association candidate held by calibration_node; frame 124".
  static constexpr const char* kCandidateMarker = "/thermal_lidar_calibration/dataset_candidate";
  // And for a frame the skip rule passed over, held for the association's final round (issue
  // 24): "skipped frame held by calibration_node for the final round; frame 125".
  static constexpr const char* kSkippedMarker = "/thermal_lidar_calibration/dataset_skipped";
};

// The marker's text for a stored frame, and the kind read back from it (a marker without a frame
// number, from an older dataset bag, is a pair in order).
std::string datasetMarkerText(const StoredFrameKind& kind);
StoredFrameKind parseDatasetMarker(const std::string& text);

class DatasetBagWriter {
 public:
  // `append`: continue an existing bag (call recoverDatasetBag first); otherwise an existing file
  // at `path` is kept as "<path>.previous" and a new bag starts with the first pair.
  DatasetBagWriter(std::string path, bool append);
  ~DatasetBagWriter();

  // Appends one pair (all five messages stamped with the image's time). Returns when the pair is
  // in the file. Throws std::runtime_error naming the path and the reason; the bag then holds
  // the pairs it held before.
  void write(const sensor_msgs::Image& image, const sensor_msgs::Image& mask,
             const sensor_msgs::PointCloud2& clusters, const sensor_msgs::CameraInfo& camera_info,
             const StoredFrameKind& kind = {});
  // Deletes the bag (and any journal); the next write() starts a new one.
  void clear();

  const std::string& path() const { return path_; }
  // The bag's index (what each append rewrites), for the benchmark and tests.
  std::size_t indexBytes() const;

 private:
  std::string path_;
  std::unique_ptr<BagAppender> appender_;
};

// If "<path>.journal" exists (the process died during an append), restores the bag from it.
// Returns true if a restore happened. Throws std::runtime_error if the journal is unusable.
bool recoverDatasetBag(const std::string& path);

struct DatasetBagContents {
  // The stored frames, decoded by the live decoder; they become pairs through
  // DatasetBuilder::restore, which checks them like live frames.
  std::vector<Frame> frames;
  // Exact image header stamps (ros::Time::toNSec) of `frames`, index for index. frame.stamp_s is
  // toSec(), which does not round-trip to nanoseconds at epoch times; de-duplicate on these.
  std::vector<std::uint64_t> pair_stamps_ns;
  // How each of `frames` was kept (its marker), index for index.
  std::vector<StoredFrameKind> kinds;
  std::optional<CameraModel> camera;    // from the last camera_info in the bag
  std::string camera_frame, lidar_frame;
  std::vector<std::string> errors;      // frames that could not be decoded (skipped)
};
// Reads a dataset bag written by DatasetBagWriter (recovering it first, unless `recover` is
// false: a reader that is not its writer must not touch a bag a node may be appending to). Throws
// std::runtime_error if the bag cannot be opened.
DatasetBagContents readDatasetBag(const std::string& path, bool recover = true);

// The pairs and the association candidates the bag at `path` holds, read back from its index
// (one marker message per frame, on a topic per kind), for answers that must be true rather than
// what the writer believes. Throws std::runtime_error naming the bag when it cannot be read.
struct DatasetBagCounts {
  std::size_t pairs = 0, candidates = 0, skipped_frames = 0;
};
DatasetBagCounts countDatasetBag(const std::string& path);

// The stored frames into `builder` (DatasetBuilder::restore, in the order they were stored):
// the one way ~resume and calibrate_bag read a dataset bag back.
struct RestoredDataset {
  std::size_t pairs = 0;       // kept as pairs
  std::size_t candidates = 0;  // held as association candidates (before the builder's bound)
  std::size_t skipped_frames = 0;  // held for the final round (issue 24; before the bound)
  std::vector<std::uint64_t> stamps_ns;  // the exact image stamps of the frames restored
  std::vector<std::string> skipped;      // why a stored frame was not restored, one line each
  bool numbered = false;  // every stored frame carried its frame number (their order and place)
};
RestoredDataset restoreDataset(DatasetBagContents contents, DatasetBuilder& builder);

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
