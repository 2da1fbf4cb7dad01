// make_synthetic_bag: renders a synthetic thermal camera + LiDAR drive among people into a ROS 1
// bag (LZ4) with the INTERFACE topics, and writes the true extrinsic to a YAML truth file.
// Bad arguments: one-line error on stderr, exit 2. Other failures: exit 1.

#include "thermal_lidar_calibration/tools/calibrate_bag_options.hpp"
#include "thermal_lidar_calibration/ros/calibrated_tf_publisher.hpp"
#include "thermal_lidar_calibration/ros/msg_conversion.hpp"
#include "thermal_lidar_calibration/app/result_file.hpp"
#include "thermal_lidar_calibration/synthetic/synthetic_rig.hpp"

#include <geometry_msgs/TransformStamped.h>
#include <boost/make_shared.hpp>
#include <rosbag/bag.h>
#include <tf2_msgs/TFMessage.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <random>
#include <stdexcept>
#include <string>
#include <sys/stat.h>
#include <vector>

namespace syn = thermal_lidar_calibration::synthetic;
namespace ros_io = thermal_lidar_calibration::ros_io;
using thermal_lidar_calibration::Extrinsic;
using thermal_lidar_calibration::ros_io::UsageError;

namespace {

const char* kUsage =
    "Usage: make_synthetic_bag --output OUT.bag [options]\n"
    "Renders a vehicle driving among people with a thermal camera and a LiDAR (ray cast) into a ROS 1\n"
    "bag (LZ4): /thermal/image_raw, /thermal/camera_info, /thermal/human_mask, /lidar/human_clusters\n"
    "[, /lidar/points, /tf_static], and writes the true extrinsic (p_C = R p_L + t) to a YAML file.\n"
    "Options:\n"
    "  --output FILE            bag to write (required)\n"
    "  --truth FILE             truth YAML (default: <bag>.truth.yaml)\n"
    "  --rig NAME               fieldsafe (640x512, HDL-32E; default) | ms2 (640x256, VLP-16)\n"
    "  --seed N                 random seed (default 1); same seed, same bag content\n"
    "  --frames N               frames at 10 Hz (default 1200)\n"
    "  --duration S             alternative to --frames: seconds of driving\n"
    "  --people N               total people in the field (default 0 = ~1.8 per group, automatic)\n"
    "  --noise PRESET           clean (default) | realistic (mask edges +-2 px, 2 cm range noise,\n"
    "                           3% missed people, 3% false clusters, 2% false mask blobs)\n"
    "  --range-noise-m X        LiDAR range noise sigma, m (overrides the preset)\n"
    "  --mask-edge-px N         random dilate/erode of each person mask by 0..N px\n"
    "  --miss-rate P            per person, per frame, per modality miss probability\n"
    "  --false-cluster-rate P   probability a post/bush in range is reported as a person cluster\n"
    "  --false-mask-rate P      per frame probability of a false person blob in the mask\n"
    "  --mask-style S           ids (default: person i = i) | binary (all persons 255)\n"
    "  --image-encoding E       mono8 (default) | mono16\n"
    "  --full-cloud             also write /lidar/points (x,y,z,intensity; decimated)\n"
    "  --no-camera-info         do not write /thermal/camera_info\n"
    "  --camera-parent FRAME    also write /tf_static with FRAME -> camera frame\n"
    "  --time-jitter-s X        random +-X s offset per topic and frame (default 0)\n"
    "  --lidar-frame F          default velodyne\n"
    "  --camera-frame F         default thermal_optical\n"
    "  --help                   this text\n";

// The rig's own defaults (frame count, frame rate), which the command line starts from.
const syn::SyntheticConfig& defaultConfig() {
  static const syn::SyntheticConfig config;
  return config;
}

struct Options {
  std::string output;
  std::string truth;
  std::string rig = "fieldsafe";
  std::uint64_t seed = 1;
  int frames = defaultConfig().frames;
  int people = 0;
  std::string noise = "clean";
  double range_noise_m = -1, miss_rate = -1, false_cluster_rate = -1, false_mask_rate = -1;
  int mask_edge_px = -1;
  std::string mask_style = "ids";
  std::string image_encoding = "mono8";
  bool full_cloud = false;
  bool camera_info = true;
  std::string camera_parent;
  double time_jitter_s = 0.0;
  std::string lidar_frame = "velodyne";
  std::string camera_frame = "thermal_optical";
};

double parseDouble(const std::string& flag, const std::string& text, double lo, double hi) {
  std::size_t used = 0;
  double v = 0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || !std::isfinite(v)) throw UsageError(flag + " needs a number, got '" + text + "'");
  if (v < lo || v > hi) {
    throw UsageError(flag + " must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " + text);
  }
  return v;
}

long long parseInt(const std::string& flag, const std::string& text, long long lo, long long hi) {
  std::size_t used = 0;
  long long v = 0;
  try {
    v = std::stoll(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size()) throw UsageError(flag + " needs an integer, got '" + text + "'");
  if (v < lo || v > hi) {
    throw UsageError(flag + " must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " + text);
  }
  return v;
}

Options parseArgs(const std::vector<std::string>& args, bool* help) {
  Options o;
  bool frames_set = false, duration_set = false;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&]() -> const std::string& {
      if (i + 1 >= args.size()) throw UsageError(a + " needs a value");
      return args[++i];
    };
    auto oneOf = [&](const std::string& v, std::initializer_list<const char*> allowed) {
      for (const char* x : allowed) {
        if (v == x) return v;
      }
      std::string list;
      for (const char* x : allowed) list += std::string(list.empty() ? "" : "|") + x;
      throw UsageError(a + " must be one of " + list + ", got '" + v + "'");
    };
    if (a == "--help" || a == "-h") {
      *help = true;
      return o;
    } else if (a == "--output") {
      o.output = value();
    } else if (a == "--truth") {
      o.truth = value();
    } else if (a == "--rig") {
      o.rig = oneOf(value(), {"fieldsafe", "ms2"});
    } else if (a == "--seed") {
      o.seed = static_cast<std::uint64_t>(parseInt(a, value(), 0, 9007199254740991LL));
    } else if (a == "--frames") {
      o.frames = static_cast<int>(parseInt(a, value(), 1, 100000));
      frames_set = true;
    } else if (a == "--duration") {
      const double seconds = parseDouble(a, value(), 0.1, 10000.0);
      // makeConfig keeps the default frame rate.
      o.frames = std::max(1, static_cast<int>(std::lround(seconds * defaultConfig().frame_rate_hz)));
      duration_set = true;
    } else if (a == "--people") {
      o.people = static_cast<int>(parseInt(a, value(), 0, 250));
    } else if (a == "--noise") {
      o.noise = oneOf(value(), {"clean", "realistic"});
    } else if (a == "--range-noise-m") {
      o.range_noise_m = parseDouble(a, value(), 0.0, 1.0);
    } else if (a == "--mask-edge-px") {
      o.mask_edge_px = static_cast<int>(parseInt(a, value(), 0, 20));
    } else if (a == "--miss-rate") {
      o.miss_rate = parseDouble(a, value(), 0.0, 1.0);
    } else if (a == "--false-cluster-rate") {
      o.false_cluster_rate = parseDouble(a, value(), 0.0, 1.0);
    } else if (a == "--false-mask-rate") {
      o.false_mask_rate = parseDouble(a, value(), 0.0, 1.0);
    } else if (a == "--mask-style") {
      o.mask_style = oneOf(value(), {"ids", "binary"});
    } else if (a == "--image-encoding") {
      o.image_encoding = oneOf(value(), {"mono8", "mono16"});
    } else if (a == "--full-cloud") {
      o.full_cloud = true;
    } else if (a == "--no-camera-info") {
      o.camera_info = false;
    } else if (a == "--camera-parent") {
      o.camera_parent = value();
    } else if (a == "--time-jitter-s") {
      o.time_jitter_s = parseDouble(a, value(), 0.0, 1.0);
    } else if (a == "--lidar-frame") {
      o.lidar_frame = value();
    } else if (a == "--camera-frame") {
      o.camera_frame = value();
    } else {
      throw UsageError("unknown argument '" + a + "' (see --help)");
    }
  }
  if (o.output.empty()) throw UsageError("--output OUT.bag is required (see --help)");
  if (frames_set && duration_set) throw UsageError("give either --frames or --duration, not both");
  if (o.lidar_frame.empty() || o.camera_frame.empty() || o.lidar_frame == o.camera_frame) {
    throw UsageError("--lidar-frame and --camera-frame must be non-empty and different");
  }
  if (!o.camera_parent.empty() && o.camera_parent == o.camera_frame) {
    throw UsageError("--camera-parent must differ from the camera frame");
  }
  if (o.truth.empty()) o.truth = o.output + ".truth.yaml";
  return o;
}

syn::SyntheticConfig makeConfig(const Options& o) {
  syn::SyntheticConfig c;
  c.rig = syn::rigByName(o.rig);
  c.seed = o.seed;
  c.frames = o.frames;
  c.scene.people = o.people;
  c.noise = syn::NoiseConfig::preset(o.noise);
  if (o.range_noise_m >= 0) c.noise.range_sigma_m = o.range_noise_m;
  if (o.mask_edge_px >= 0) c.noise.mask_edge_px = o.mask_edge_px;
  if (o.miss_rate >= 0) c.noise.miss_rate = o.miss_rate;
  if (o.false_cluster_rate >= 0) c.noise.false_cluster_rate = o.false_cluster_rate;
  if (o.false_mask_rate >= 0) c.noise.false_mask_rate = o.false_mask_rate;
  c.mask_style = o.mask_style == "binary" ? syn::MaskStyle::kBinary : syn::MaskStyle::kIds;
  c.image_depth = o.image_encoding == "mono16" ? syn::ImageDepth::kMono16 : syn::ImageDepth::kMono8;
  c.full_cloud = o.full_cloud;
  return c;
}

void writeTruth(const Options& o, const syn::SyntheticRig& rig) {
  const syn::SyntheticConfig& c = rig.config();
  YAML::Emitter out;
  out.SetDoublePrecision(15);
  out << YAML::Comment("Ground truth of a make_synthetic_bag run: p_C = R p_L + t (metres, radians)");
  out << YAML::BeginMap;
  out << YAML::Key << "lidar_frame" << YAML::Value << o.lidar_frame;
  out << YAML::Key << "camera_frame" << YAML::Value << o.camera_frame;
  thermal_lidar_calibration::emitExtrinsic(out, c.rig.truth);
  out << YAML::Key << "rig" << YAML::Value << c.rig.name;
  out << YAML::Key << "rig_description" << YAML::Value << c.rig.description;
  out << YAML::Key << "lidar_model" << YAML::Value << c.rig.lidar.name;
  out << YAML::Key << "lidar_height_m" << YAML::Value << c.rig.lidar_height_m;
  out << YAML::Key << "seed" << YAML::Value << c.seed;
  out << YAML::Key << "frames" << YAML::Value << c.frames;
  out << YAML::Key << "frame_rate_hz" << YAML::Value << c.frame_rate_hz;
  out << YAML::Key << "people" << YAML::Value << rig.scene().people().size();
  out << YAML::Key << "noise" << YAML::Value << o.noise;
  out << YAML::Key << "range_noise_m" << YAML::Value << c.noise.range_sigma_m;
  out << YAML::Key << "mask_edge_px" << YAML::Value << c.noise.mask_edge_px;
  out << YAML::Key << "miss_rate" << YAML::Value << c.noise.miss_rate;
  out << YAML::Key << "false_cluster_rate" << YAML::Value << c.noise.false_cluster_rate;
  out << YAML::Key << "false_mask_rate" << YAML::Value << c.noise.false_mask_rate;
  const auto& cam = c.rig.camera;
  out << YAML::Key << "image_width" << YAML::Value << cam.width;
  out << YAML::Key << "image_height" << YAML::Value << cam.height;
  const double camera_matrix[9] = {cam.fx, cam.skew, cam.cx, 0.0, cam.fy, cam.cy, 0.0, 0.0, 1.0};
  thermal_lidar_calibration::emitVector(out, "camera_matrix", camera_matrix, 9);
  out << YAML::Key << "distortion_model" << YAML::Value << "plumb_bob";
  thermal_lidar_calibration::emitVector(out, "distortion_coefficients", cam.distortion.data(), 5);
  out << YAML::Key << "bag" << YAML::Value << o.output;
  out << YAML::EndMap;
  std::ofstream file(o.truth);
  if (!file) throw std::runtime_error("cannot write truth file '" + o.truth + "'");
  file << out.c_str() << "\n";
  if (!file) throw std::runtime_error("failed writing truth file '" + o.truth + "'");
}

// The connection header `rosbag record` stores for a latched topic: `rosbag play` then
// republishes it latched, so a node that subscribes after the first instant still receives it.
template <typename Msg>
boost::shared_ptr<ros::M_string> latchedConnectionHeader() {
  auto header = boost::make_shared<ros::M_string>();
  (*header)["type"] = ros::message_traits::datatype<Msg>();
  (*header)["md5sum"] = ros::message_traits::md5sum<Msg>();
  (*header)["message_definition"] = ros::message_traits::definition<Msg>();
  (*header)["callerid"] = "/make_synthetic_bag";
  (*header)["latching"] = "1";
  return header;
}

tf2_msgs::TFMessage staticTransform(const Options& o, const Extrinsic& truth, double stamp_s) {
  // The camera's pose in its parent, as if the parent were the LiDAR frame: T_lidar_camera, the
  // same transform calibration_node publishes.
  tf2_msgs::TFMessage msg;
  msg.transforms.push_back(
      ros_io::toTransformMsg(truth, o.camera_parent, o.camera_frame, ros::Time(stamp_s)));
  return msg;
}

int run(const Options& o) {
  const auto start = std::chrono::steady_clock::now();
  const syn::SyntheticRig rig(makeConfig(o));  // throws std::invalid_argument on bad settings
  const syn::SyntheticConfig& c = rig.config();

  rosbag::Bag bag;
  bag.open(o.output, rosbag::bagmode::Write);
  bag.setCompression(rosbag::compression::LZ4);
  if (!o.camera_parent.empty()) {
    // One message before everything else (what a latched /tf_static looks like in a bag).
    const double tf_stamp_s = c.start_stamp_s - o.time_jitter_s - 0.01;
    bag.write("/tf_static", ros::Time(tf_stamp_s), staticTransform(o, c.rig.truth, tf_stamp_s),
              latchedConnectionHeader<tf2_msgs::TFMessage>());
  }
  const sensor_msgs::CameraInfo info_template = ros_io::cameraInfoFromModel(c.rig.camera);

  std::vector<int> mask_people, cluster_people;
  constexpr int kBatch = 32;
  std::vector<syn::SyntheticFrame> batch;
  for (int first = 0; first < c.frames; first += kBatch) {
    const int n = std::min(kBatch, c.frames - first);
    batch.assign(static_cast<std::size_t>(n), syn::SyntheticFrame{});
#pragma omp parallel for schedule(dynamic)
    for (int k = 0; k < n; ++k) batch[static_cast<std::size_t>(k)] = rig.render(first + k);
    for (const auto& f : batch) {
      std::mt19937_64 jitter_rng(syn::mixSeed(c.seed, 11, static_cast<std::uint64_t>(f.index)));
      std::uniform_real_distribution<double> jitter(-o.time_jitter_s, o.time_jitter_s);
      auto stampFor = [&]() { return o.time_jitter_s > 0.0 ? f.stamp_s + jitter(jitter_rng) : f.stamp_s; };
      const double t_image = stampFor(), t_mask = stampFor(), t_clusters = stampFor();
      bag.write("/thermal/image_raw", ros::Time(t_image), ros_io::encodeMonoImage(f.image, o.camera_frame, t_image));
      if (o.camera_info) {
        sensor_msgs::CameraInfo info = info_template;
        info.header.frame_id = o.camera_frame;
        info.header.stamp = ros::Time(t_image);
        bag.write("/thermal/camera_info", info.header.stamp, info);
      }
      bag.write("/thermal/human_mask", ros::Time(t_mask), ros_io::encodeMonoImage(f.mask, o.camera_frame, t_mask));
      bag.write("/lidar/human_clusters", ros::Time(t_clusters),
                ros_io::encodeClusters(f.cluster_points, f.cluster_labels, o.lidar_frame, t_clusters));
      if (c.full_cloud) {
        bag.write("/lidar/points", ros::Time(t_clusters),
                  ros_io::encodePointsWithIntensity(f.full_points, f.full_intensity, o.lidar_frame, t_clusters));
      }
      mask_people.push_back(f.mask_people);
      cluster_people.push_back(f.cluster_people);
    }
    std::fprintf(stderr, "\rmake_synthetic_bag: %d/%d frames", first + n, c.frames);
  }
  bag.close();
  std::fprintf(stderr, "\n");
  writeTruth(o, rig);

  struct stat st {};
  const double size_mb = ::stat(o.output.c_str(), &st) == 0 ? st.st_size / 1e6 : 0.0;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("wrote %s (%.1f MB) and %s in %.1f s\n", o.output.c_str(), size_mb, o.truth.c_str(), seconds);
  std::printf("rig %s, seed %llu, %d frames, %zu people; frames with equal mask/cluster counts in 1..3: %d; "
              "pairs under the default gate (skip 3): %d\n",
              c.rig.name.c_str(), static_cast<unsigned long long>(c.seed), c.frames, rig.scene().people().size(),
              syn::countEqualFrames(mask_people, cluster_people, 3),
              syn::countGatedPairs(mask_people, cluster_people, 3, 3));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  try {
    bool help = false;
    options = parseArgs(std::vector<std::string>(argv + 1, argv + argc), &help);
    if (help) {
      std::fputs(kUsage, stdout);
      return 0;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_synthetic_bag: %s\n", e.what());
    return 2;
  }
  try {
    return run(options);
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "make_synthetic_bag: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_synthetic_bag: %s\n", e.what());
    return 1;
  }
}
