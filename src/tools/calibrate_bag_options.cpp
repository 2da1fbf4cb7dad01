// calibrate_bag command-line parsing: "--flag value" or "--flag=value".

#include "thermal_lidar_calibration/tools/calibrate_bag_options.hpp"

#include <limits>
#include <vector>

namespace thermal_lidar_calibration {
namespace ros_io {
namespace {

long long parseInteger(const std::string& flag, const std::string& value, long long lo,
                       long long hi) {
  std::size_t used = 0;
  long long v = 0;
  try {
    v = std::stoll(value, &used, 10);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != value.size() || v < lo || v > hi) {
    throw UsageError(flag + " '" + value + "': must be an integer in [" + std::to_string(lo) +
                     ", " + std::to_string(hi) + "]");
  }
  return v;
}

}  // namespace

std::string calibrateBagUsage() {
  return
      "usage: calibrate_bag --bag IN.bag --output OUT.yaml [options]\n"
      "\n"
      "Calibrates a thermal camera against a 3D LiDAR from people seen by both, offline, with\n"
      "the same pairing, gating and optimizer as calibration_node. No roscore needed.\n"
      "\n"
      "  --bag IN.bag             ROS 1 bag with image, mask, clusters (and camera_info)\n"
      "  --output OUT.yaml        result file (rotation_vector, translation, loss, ...)\n"
      "  --config PARAMS.yaml     parameters, flat keys as in config/default.yaml\n"
      "  --image-topic T          thermal image        (default /thermal/image_raw)\n"
      "  --mask-topic T           person mask          (default /thermal/human_mask)\n"
      "  --clusters-topic T       labelled person cloud (default /lidar/human_clusters)\n"
      "  --camera-info-topic T    intrinsics in the bag (default /thermal/camera_info)\n"
      "  --detect                 find the people with the built-in detectors on the raw image\n"
      "                           and points (no mask/clusters topics needed; detector keys and\n"
      "                           thermal_input_flip in --config)\n"
      "  --points-topic T         raw LiDAR cloud for --detect (default /lidar/points)\n"
      "  --camera-info FILE.yaml  intrinsics from a camera_calibration file (wins over the bag)\n"
      "  --algorithm 1|2          1: evolution only; 2: with outlier rejection (default 2)\n"
      "  --refine none|local      local refinement after the evolution (default local)\n"
      "  --seed N                 random seed (default 1)\n"
      "  --threads N              loss threads, 0 = all cores (results do not depend on it)\n"
      "  --truth TRUTH.yaml       known extrinsic: print rotation/translation errors and its loss\n"
      "  --reference FILE.yaml    the calibration you already have (a result YAML): its difference\n"
      "                           per axis and its loss on the same pairs, beside ours\n"
      "  --report DIR             write a visual report into DIR: overlays of the best and worst\n"
      "                           pairs, coverage, convergence, loss per pair, uncertainty, and an\n"
      "                           index.html with the numbers\n"
      "  --monitor                drift watch instead of a calibration: the kept pairs in time order\n"
      "                           against --reference; writes OUT.yaml (latest fit + drift state),\n"
      "                           OUT.drift.csv and OUT.drift.png (monitor_* keys in --config)\n"
      "  --quiet                  only errors and warnings\n"
      "  --help                   this text\n"
      "\n"
      "Exit codes: 0 success, 1 bad input or calibration failure, 2 usage error.\n";
}

CalibrateBagOptions parseCalibrateBagOptions(int argc, const char* const* argv) {
  CalibrateBagOptions o;
  std::vector<std::string> args(argv + 1, argv + argc);
  for (std::size_t i = 0; i < args.size(); ++i) {
    std::string flag = args[i];
    std::optional<std::string> inline_value;
    const std::size_t eq = flag.find('=');
    if (flag.rfind("--", 0) == 0 && eq != std::string::npos) {
      inline_value = flag.substr(eq + 1);
      flag = flag.substr(0, eq);
    }
    if (flag == "--help" || flag == "-h") {
      o.help = true;
      return o;
    }
    if (flag == "--quiet" || flag == "-q") {
      o.quiet = true;
      continue;
    }
    if (flag == "--detect") {
      o.detect = true;
      continue;
    }
    if (flag == "--monitor") {
      o.monitor = true;
      continue;
    }
    const auto value = [&]() -> std::string {
      if (inline_value) return *inline_value;
      if (i + 1 >= args.size()) throw UsageError(flag + " needs a value");
      return args[++i];
    };
    if (flag == "--bag") {
      o.bag = value();
    } else if (flag == "--output") {
      o.output = value();
    } else if (flag == "--config") {
      o.config = value();
    } else if (flag == "--image-topic") {
      o.image_topic = value();
    } else if (flag == "--mask-topic") {
      o.mask_topic = value();
    } else if (flag == "--clusters-topic") {
      o.clusters_topic = value();
    } else if (flag == "--camera-info-topic") {
      o.camera_info_topic = value();
    } else if (flag == "--points-topic") {
      o.points_topic = value();
    } else if (flag == "--camera-info") {
      o.camera_info_file = value();
    } else if (flag == "--algorithm") {
      const std::string v = value();
      if (v != "1" && v != "2") throw UsageError("--algorithm '" + v + "': must be 1 or 2");
      o.algorithm = v == "1" ? 1 : 2;
    } else if (flag == "--refine") {
      const std::string v = value();
      if (v != "none" && v != "local") {
        throw UsageError("--refine '" + v + "': must be none or local");
      }
      o.refine = v;
    } else if (flag == "--seed") {
      o.seed = static_cast<std::uint64_t>(
          parseInteger("--seed", value(), 0, std::numeric_limits<long long>::max()));
    } else if (flag == "--threads") {
      o.threads = static_cast<int>(parseInteger("--threads", value(), 0, 1024));
    } else if (flag == "--truth") {
      o.truth = value();
    } else if (flag == "--reference") {
      o.reference = value();
    } else if (flag == "--report") {
      o.report = value();
    } else {
      throw UsageError("unknown argument '" + args[i] + "'");
    }
  }
  if (o.bag.empty()) throw UsageError("--bag IN.bag is required");
  if (o.output.empty()) throw UsageError("--output OUT.yaml is required");
  if (o.monitor && !o.report.empty()) {
    throw UsageError("--report is for a calibration; --monitor writes OUT.drift.png instead");
  }
  if (o.monitor && o.reference.empty()) {
    throw UsageError("--monitor needs --reference RESULT.yaml: the extrinsic in use, to watch for drift");
  }
  for (std::string* topic :
       {&o.image_topic, &o.mask_topic, &o.clusters_topic, &o.camera_info_topic, &o.points_topic}) {
    if (topic->empty()) throw UsageError("topic names must not be empty");
    if ((*topic)[0] != '/') *topic = "/" + *topic;  // bag topics are absolute
  }
  return o;
}

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
