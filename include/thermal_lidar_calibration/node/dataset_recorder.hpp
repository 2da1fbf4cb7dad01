#pragma once
// The node's side of ~dataset_bag: appends each kept pair through DatasetBagWriter and keeps an
// honest account of what the bag holds. A write that fails (a full disk, a removed directory)
// never ends the node: recording stops, the reason (path and free space) goes to ~status,
// /diagnostics and a throttled error, and the node keeps collecting in memory, where every kept
// pair stays.

#include "thermal_lidar_calibration/node/node_diagnostics.hpp"
#include "thermal_lidar_calibration/ros/dataset_bag.hpp"

#include <cstdint>
#include <memory>
#include <string>

namespace thermal_lidar_calibration {
namespace ros_io {

class DatasetRecorder {
 public:
  // `path` "" = do not record. `append`: continue the bag (~resume) that holds `pairs_in_bag`.
  DatasetRecorder(const std::string& path, bool append, std::size_t pairs_in_bag);

  // Appends one kept pair, or a frame held as an association candidate (`kind`); false if it is
  // not on disk (recording off or stopped, or this write failed: then recording stops and the
  // error is logged).
  bool record(const sensor_msgs::Image& image, const sensor_msgs::Image& mask,
              const sensor_msgs::PointCloud2& clusters, const sensor_msgs::CameraInfo& info,
              const StoredFrameKind& kind = {});
  // ~reset: deletes the bag; recording starts again with the next pair. Returns what happened,
  // in words ("deleted <path>", "<path> did not exist", the error).
  std::string clear();

  bool enabled() const { return writer_ != nullptr; }
  bool recording() const { return enabled() && stop_reason_.empty(); }
  const std::string& path() const { return path_; }
  std::size_t pairsInBag() const { return pairs_in_bag_; }
  std::size_t pairsNotRecorded() const { return pairs_not_recorded_; }
  // "" while recording (or when off); else why recording stopped, with path and free space.
  const std::string& stopReason() const { return stop_reason_; }

  // For ~save: what the bag on disk holds, read back from the file (not the writer's count), in
  // words: "the dataset bag <path> holds 12 of the 15 kept pairs [and 4 association candidates]
  // (recording stopped: ...)", or
  // that there is no bag on disk, or that it cannot be read. "" when not recording.
  std::string describeOnDisk(std::size_t pairs_kept) const;

  void diagnose(NodeDiagnostics::Status& status) const;

 private:
  std::string path_;
  std::unique_ptr<DatasetBagWriter> writer_;
  std::size_t pairs_in_bag_ = 0;
  std::size_t pairs_not_recorded_ = 0;  // kept since recording stopped (in memory only)
  std::string stop_reason_;
};

// "3.2 MB free on the file system of /data" (statvfs of the path's directory), or why unknown.
std::string freeSpaceText(const std::string& path);

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
