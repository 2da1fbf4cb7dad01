#pragma once
// Command line of calibrate_bag.

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>

namespace thermal_lidar_calibration {
namespace ros_io {

struct CalibrateBagOptions {
  std::string bag;
  std::string output;
  std::string config;            // --config PARAMS.yaml (flat keys, as config/default.yaml)
  std::string image_topic = "/thermal/image_raw";
  std::string mask_topic = "/thermal/human_mask";
  std::string clusters_topic = "/lidar/human_clusters";
  std::string camera_info_topic = "/thermal/camera_info";
  std::string points_topic = "/lidar/points";  // raw cloud, read with --detect
  bool detect = false;   // --detect: the built-in person detectors on the raw image and points
  bool monitor = false;  // --monitor: the drift watch against --reference instead of a calibration
  std::string camera_info_file;  // --camera-info: wins over the bag's CameraInfo
  std::optional<int> algorithm;  // 1 | 2
  std::optional<std::string> refine;  // none | local
  std::optional<std::uint64_t> seed;
  std::optional<int> threads;
  std::string truth;             // --truth TRUTH.yaml: report errors against it
  std::string reference;         // --reference RESULT.yaml: the calibration the user already has
  std::string report;            // --report DIR: the visual report (pictures and index.html)
  bool quiet = false;
  bool help = false;
};

// A command-line mistake: the tool prints it (calibrate_bag with the usage hint) and exits with
// code 2. make_synthetic_bag's argument parser throws it too.
class UsageError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// Throws UsageError. With --help, returns options with help = true and nothing else checked.
CalibrateBagOptions parseCalibrateBagOptions(int argc, const char* const* argv);
std::string calibrateBagUsage();

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
