// DatasetRecorder: ~dataset_bag from the node's side; a failed write stops recording, never
// the node.

#include "thermal_lidar_calibration/node/dataset_recorder.hpp"

#include <diagnostic_msgs/DiagnosticStatus.h>
#include <ros/console.h>

#include <sys/statvfs.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace thermal_lidar_calibration {
namespace ros_io {

std::string freeSpaceText(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  const std::string dir =
      slash == std::string::npos ? "." : (slash == 0 ? "/" : path.substr(0, slash));
  struct statvfs fs {};
  if (::statvfs(dir.c_str(), &fs) != 0) {
    return "free space of " + dir + " unknown (" + std::strerror(errno) + ")";
  }
  const double free_bytes = static_cast<double>(fs.f_bavail) * static_cast<double>(fs.f_frsize);
  char text[64];
  std::snprintf(text, sizeof(text), "%.1f MB free", free_bytes / 1e6);
  return std::string(text) + " on the file system of " + dir;
}

DatasetRecorder::DatasetRecorder(const std::string& path, bool append, std::size_t pairs_in_bag)
    : path_(path), pairs_in_bag_(append ? pairs_in_bag : 0) {
  if (path_.empty()) return;
  writer_ = std::make_unique<DatasetBagWriter>(path_, append);  // throws: the node cannot start
}

bool DatasetRecorder::record(const sensor_msgs::Image& image, const sensor_msgs::Image& mask,
                             const sensor_msgs::PointCloud2& clusters,
                             const sensor_msgs::CameraInfo& info, const StoredFrameKind& kind) {
  if (!writer_) return false;
  if (!stop_reason_.empty()) {
    if (kind.candidate) return false;  // the account below is of the pairs
    ++pairs_not_recorded_;
    ROS_ERROR_THROTTLE(30.0, "not recording (%s); %zu kept pairs are in memory only (the bag "
                             "holds %zu)",
                       stop_reason_.c_str(), pairs_not_recorded_, pairs_in_bag_);
    return false;
  }
  try {
    writer_->write(image, mask, clusters, info, kind);
    if (!kind.candidate) ++pairs_in_bag_;
    return true;
  } catch (const std::exception& e) {
    if (!kind.candidate) ++pairs_not_recorded_;
    stop_reason_ = std::string(e.what()) + "; " + freeSpaceText(path_);
    // e.what() names the bag.
    ROS_ERROR("recording stopped: %s. The node keeps collecting: the bag holds its first %zu "
              "pairs; later ones are kept in memory and used for the result, but are not in the "
              "bag",
              stop_reason_.c_str(), pairs_in_bag_);
    return false;
  }
}

std::string DatasetRecorder::clear() {
  if (!writer_) return "";
  const bool existed = ::access(path_.c_str(), F_OK) == 0;
  try {
    writer_->clear();
  } catch (const std::exception& e) {
    return std::string("could not delete the dataset bag: ") + e.what();
  }
  pairs_in_bag_ = 0;
  pairs_not_recorded_ = 0;
  stop_reason_.clear();
  return existed ? "deleted " + path_ : path_ + " did not exist yet";
}

std::string DatasetRecorder::describeOnDisk(std::size_t pairs_kept) const {
  if (!writer_) return "";
  const std::string stopped =
      stop_reason_.empty() ? "" : " (recording stopped: " + stop_reason_ + ")";
  if (::access(path_.c_str(), F_OK) != 0) {
    return "no dataset bag on disk (" + path_ + " is written with the next kept pair)" + stopped;
  }
  try {
    const DatasetBagCounts on_disk = countDatasetBag(path_);
    return "the dataset bag " + path_ + " holds " + std::to_string(on_disk.pairs) + " of the " +
           std::to_string(pairs_kept) + " kept pairs" +
           (on_disk.candidates > 0 ? " and " + std::to_string(on_disk.candidates) + " association candidates" : "") +
           (on_disk.skipped_frames > 0 ? " and " + std::to_string(on_disk.skipped_frames) + " skipped frames" : "") +
           stopped;
  } catch (const std::exception& e) {
    return "the dataset bag cannot be read back: " + std::string(e.what()) + stopped;
  }
}

void DatasetRecorder::diagnose(NodeDiagnostics::Status& status) const {
  using diagnostic_msgs::DiagnosticStatus;
  if (!writer_) {
    status.summary(DiagnosticStatus::OK, "not recording (~dataset_bag is empty)");
  } else if (!stop_reason_.empty()) {
    status.summaryf(DiagnosticStatus::ERROR,
                    "recording stopped: %zu kept pairs are in memory only",
                    pairs_not_recorded_);
    status.add("reason", stop_reason_);
  } else {
    status.summaryf(DiagnosticStatus::OK, "recording: %zu pairs in the bag", pairs_in_bag_);
  }
  status.add("dataset_bag", path_);
  status.add("pairs_in_bag", pairs_in_bag_);
  status.add("pairs_not_recorded", pairs_not_recorded_);
}

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
