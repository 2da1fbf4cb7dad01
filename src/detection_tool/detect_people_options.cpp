#include "thermal_lidar_calibration/detection_tool/detect_people.hpp"

#include <cmath>
#include <functional>
#include <map>

namespace thermal_lidar_calibration {
namespace detection_tool {
namespace {

double parseNumber(const std::string& flag, const std::string& text) {
  std::size_t used = 0;
  double value = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || text.empty() || !std::isfinite(value)) {
    throw UsageError(flag + " '" + text + "': not a number");
  }
  return value;
}

}  // namespace

const char* detectPeopleUsage() {
  return "usage: detect_people --image IMG --mask-out MASK.png [--kelvin-per-count K] [--kelvin-offset O]\n"
         "                     [--flip none|vertical|horizontal|both] [--overlay-out VIEW.png] [--explain]\n"
         "                     [--config PARAMS.yaml]\n"
         "       detect_people --cloud CLOUD.pcd|CLOUD.bin --clusters-out OUT.pcd [--view-out VIEW.png] [--explain]\n"
         "                     [--config PARAMS.yaml]\n";
}

std::optional<DetectPeopleOptions> parseDetectPeopleArgs(const std::vector<std::string>& args) {
  DetectPeopleOptions o;
  const std::map<std::string, std::function<void(const std::string&)>> with_value = {
      {"--image", [&](const std::string& v) { o.image = v; }},
      {"--mask-out", [&](const std::string& v) { o.mask_out = v; }},
      {"--kelvin-per-count", [&](const std::string& v) { o.kelvin_per_count = parseNumber("--kelvin-per-count", v); }},
      {"--kelvin-offset", [&](const std::string& v) { o.kelvin_offset = parseNumber("--kelvin-offset", v); }},
      {"--flip",
       [&](const std::string& v) {
         try {
           o.flip = detection::parseImageFlip(v);
         } catch (const std::invalid_argument& e) {
           throw UsageError(std::string("--flip: ") + e.what());
         }
       }},
      {"--overlay-out", [&](const std::string& v) { o.overlay_out = v; }},
      {"--cloud", [&](const std::string& v) { o.cloud = v; }},
      {"--clusters-out", [&](const std::string& v) { o.clusters_out = v; }},
      {"--view-out", [&](const std::string& v) { o.view_out = v; }},
      {"--config", [&](const std::string& v) { o.config = v; }},
  };
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& flag = args[i];
    if (flag == "--help" || flag == "-h") return std::nullopt;
    if (flag == "--explain") {
      o.explain = true;
      continue;
    }
    const auto it = with_value.find(flag);
    if (it == with_value.end()) throw UsageError("unknown option '" + flag + "'");
    if (i + 1 >= args.size()) throw UsageError(flag + " needs a value");
    it->second(args[++i]);
  }
  const bool image = !o.image.empty(), cloud = !o.cloud.empty();
  if (image == cloud) throw UsageError("give exactly one of --image and --cloud");
  if (image && o.mask_out.empty()) throw UsageError("--image needs --mask-out MASK.png");
  if (cloud && o.clusters_out.empty()) throw UsageError("--cloud needs --clusters-out OUT.pcd");
  if (image && (!o.clusters_out.empty() || !o.view_out.empty())) {
    throw UsageError("--clusters-out and --view-out go with --cloud");
  }
  if (cloud && (!o.mask_out.empty() || !o.overlay_out.empty() || o.kelvin_per_count || o.kelvin_offset ||
                o.flip != detection::ImageFlip::kNone)) {
    throw UsageError("--mask-out, --overlay-out, --kelvin-per-count, --kelvin-offset and --flip go with --image");
  }
  return o;
}

}  // namespace detection_tool
}  // namespace thermal_lidar_calibration
