#pragma once
// detect_people: the person detectors on single files, for trying and tuning them (contract:
// docs/INTERFACE.md, "Raw sensor front-end").
//   detect_people --image IMG --mask-out MASK.png [--kelvin-per-count K] [--kelvin-offset O]
//                 [--flip none|vertical|horizontal|both] [--overlay-out VIEW.png] [--explain]
//                 [--config PARAMS.yaml]
//   detect_people --cloud CLOUD --clusters-out OUT.pcd [--view-out VIEW.png] [--explain] [--config PARAMS.yaml]
// stdout: one line per person, or "no person found"; exit 0. Bad input: one line on stderr,
// exit 1. A bad command line: one line and the usage on stderr, exit 2.

#include "thermal_lidar_calibration/detection/image_flip.hpp"

#include <optional>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

namespace thermal_lidar_calibration {
namespace detection_tool {

struct DetectPeopleOptions {
  std::string image;         // --image
  std::string mask_out;      // --mask-out
  std::optional<double> kelvin_per_count;  // --kelvin-per-count (overrides the config file)
  std::optional<double> kelvin_offset;     // --kelvin-offset
  detection::ImageFlip flip = detection::ImageFlip::kNone;  // --flip (the mask is written flipped too)
  std::string overlay_out;   // --overlay-out: the mask over the image, BGR
  std::string cloud;         // --cloud
  std::string clusters_out;  // --clusters-out
  std::string view_out;      // --view-out: bird's-eye view of the scan
  bool explain = false;      // --explain: print the levels and the rejected regions / objects to stderr
  std::string config;        // --config
};

// A command line that cannot be run (unknown option, missing value, both or neither input).
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

const char* detectPeopleUsage();
// Throws UsageError. Returns nullopt for --help.
std::optional<DetectPeopleOptions> parseDetectPeopleArgs(const std::vector<std::string>& args);
// Runs one detector; throws std::invalid_argument on bad input.
void runDetectPeople(const DetectPeopleOptions& options, std::ostream& out, std::ostream& err);
// The whole program: parse, run, report; returns the exit code.
int detectPeopleMain(int argc, char** argv, std::ostream& out, std::ostream& err);

}  // namespace detection_tool
}  // namespace thermal_lidar_calibration
