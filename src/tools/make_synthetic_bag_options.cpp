// make_synthetic_bag command-line parsing: "--flag value"; every mistake is a one-line UsageError.

#include "thermal_lidar_calibration/tools/make_synthetic_bag_options.hpp"

#include "thermal_lidar_calibration/tools/calibrate_bag_options.hpp"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <stdexcept>

namespace thermal_lidar_calibration {
namespace ros_io {
namespace {

namespace syn = synthetic;

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

std::string oneOf(const std::string& flag, const std::string& value, std::initializer_list<const char*> allowed) {
  for (const char* x : allowed) {
    if (value == x) return value;
  }
  std::string list;
  for (const char* x : allowed) list += std::string(list.empty() ? "" : "|") + x;
  throw UsageError(flag + " must be one of " + list + ", got '" + value + "'");
}

// "ROT_DEG,TRANS_CM": two non-negative numbers, not both zero.
void parseExtrinsicChange(const std::string& flag, const std::string& text, MakeSyntheticBagOptions& o) {
  const std::size_t comma = text.find(',');
  if (comma == std::string::npos || text.find(',', comma + 1) != std::string::npos) {
    throw UsageError(flag + " needs ROT_DEG,TRANS_CM (e.g. 0.5,3), got '" + text + "'");
  }
  o.extrinsic_change_rotation_deg = parseDouble(flag + " ROT_DEG", text.substr(0, comma), 0.0, 45.0);
  o.extrinsic_change_translation_cm = parseDouble(flag + " TRANS_CM", text.substr(comma + 1), 0.0, 100.0);
  if (o.extrinsic_change_rotation_deg == 0.0 && o.extrinsic_change_translation_cm == 0.0) {
    throw UsageError(flag + " 0,0 changes nothing: give a rotation or a translation");
  }
}

// Checks that need every option: conflicts and derived defaults.
void finish(MakeSyntheticBagOptions& o, bool change_given, bool cut_given, double frame_rate_hz) {
  if (o.output.empty()) throw UsageError("--output OUT.bag is required (see --help)");
  if (o.lidar_frame.empty() || o.camera_frame.empty() || o.lidar_frame == o.camera_frame) {
    throw UsageError("--lidar-frame and --camera-frame must be non-empty and different");
  }
  if (!o.camera_parent.empty() && o.camera_parent == o.camera_frame) {
    throw UsageError("--camera-parent must differ from the camera frame");
  }
  if (o.truth.empty()) o.truth = o.output + ".truth.yaml";
  if ((o.extrinsic_change_at_s >= 0.0) != change_given) {
    throw UsageError("--extrinsic-change-at S and --extrinsic-change ROT_DEG,TRANS_CM go together");
  }
  const double duration_s = o.frames / frame_rate_hz;
  if (change_given && !(o.extrinsic_change_at_s > 0.0 && o.extrinsic_change_at_s < duration_s)) {
    throw UsageError("--extrinsic-change-at must be inside the drive, between 0 and " + std::to_string(duration_s) +
                     " s (the drive's length), got " + std::to_string(o.extrinsic_change_at_s));
  }
  // Per-point times come from a sweep; a Velodyne driver stamps the sweep's end by default.
  if (o.lidar_point_time && o.lidar_stamp == "instant") o.lidar_stamp = "end";
  if (cut_given && o.lidar_stamp == "instant") {
    throw UsageError("--lidar-cut-azimuth needs a sweeping scan: add --lidar-stamp start|end or --lidar-point-time");
  }
}

}  // namespace

std::string makeSyntheticBagUsage() {
  return
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
      "  --mask-edge-sign S       both (default) | grow (dilate only) | shrink (erode only)\n"
      "  --mask-erosion-part P    all (default) | thin (only the parts narrower than the erosion\n"
      "                           are lost) | outline (eroded, those thin parts kept)\n"
      "  --miss-rate P            per person, per frame, per modality miss probability\n"
      "  --false-cluster-rate P   probability a post/bush in range is reported as a person cluster\n"
      "  --false-mask-rate P      per frame probability of a false person blob in the mask\n"
      "  --mask-style S           ids (default: person i = i) | binary (all persons 255)\n"
      "  --image-encoding E       mono8 (default) | mono16\n"
      "  --full-cloud             also write /lidar/points (x,y,z,intensity; decimated)\n"
      "  --raw                    raw sensor data for calibrate_bag --detect: /lidar/points at full\n"
      "                           density within 40 m (x,y,z,intensity,ring,truth_id) and a\n"
      "                           radiometric mono16 /thermal/image_raw (0.04 K per count), with\n"
      "                           warm confounders (sun-heated posts, parked vehicles with a hot\n"
      "                           engine, animals at body temperature); ~1.2 MB per frame in the bag\n"
      "  --no-camera-info         do not write /thermal/camera_info\n"
      "  --camera-parent FRAME    also write /tf_static with FRAME -> camera frame\n"
      "  --time-jitter-s X        random +-X s offset per topic and frame (default 0)\n"
      "  --lidar-frame F          default velodyne\n"
      "  --camera-frame F         default thermal_optical\n"
      "  --extrinsic-change-at S  a bump S seconds after the start of the drive (with --extrinsic-change)\n"
      "  --extrinsic-change ROT_DEG,TRANS_CM\n"
      "                           the camera turns ROT_DEG about a random axis and shifts TRANS_CM in\n"
      "                           a random direction (drawn from the seed); the truth file keeps the\n"
      "                           extrinsic at the start and adds extrinsic_change: {at_stamp, after, ...}\n"
      "  --empty-image-region R   left | centre | right: nobody is ever seen in that third of the image\n"
      "                           (people stand on the other side of the path; frames where someone\n"
      "                           would show there leave them out; no false detections there)\n"
      "  --camera-time-offset S   the image (and mask) stamped t shows the world at t + S, |S| <= 0.5\n"
      "                           (the time_offset_s a calibration should find; default 0)\n"
      "  --lidar-stamp start|end  the scan sweeps over one rotation (100 ms, clockwise from behind the\n"
      "                           vehicle: the camera's view is swept mid-rotation) and is stamped at\n"
      "                           its first point (Ouster) or its last (the velodyne driver); points\n"
      "                           are not motion-compensated. Default: instantaneous at the stamp\n"
      "  --lidar-point-time       each point of /lidar/points and /lidar/human_clusters carries float32\n"
      "                           `time` = capture time - header stamp, s (velodyne's field); implies a\n"
      "                           sweep, stamped at its end unless --lidar-stamp says otherwise\n"
      "  --lidar-cut-azimuth DEG  where a sweep starts and ends, counter-clockwise from straight ahead\n"
      "                           (default 180: behind; 0 cuts the camera's view in two)\n"
      "  --speed-profile P        steady (default: one speed, the drive as it always was) | field (stops,\n"
      "                           speed changes 0-1.2x the rig's speed, a meandering path and eased\n"
      "                           turns, also while people are in view)\n"
      "  --walking-fraction F     share of people walking back and forth (default 0.35); steady with 0\n"
      "                           is the drive whose timing cannot be told from the translation\n"
      "  --help                   this text\n"
      "Exit codes: 0 success, 1 failure while writing, 2 bad arguments.\n";
}

MakeSyntheticBagOptions parseMakeSyntheticBagOptions(const std::vector<std::string>& args) {
  MakeSyntheticBagOptions o;
  const double frame_rate_hz = syn::SyntheticConfig{}.frame_rate_hz;
  bool frames_set = false, duration_set = false, change_given = false, cut_given = false;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&]() -> const std::string& {
      if (i + 1 >= args.size()) throw UsageError(a + " needs a value");
      return args[++i];
    };
    if (a == "--help" || a == "-h") {
      o.help = true;
      return o;
    } else if (a == "--output") {
      o.output = value();
    } else if (a == "--truth") {
      o.truth = value();
    } else if (a == "--rig") {
      o.rig = oneOf(a, value(), {"fieldsafe", "ms2"});
    } else if (a == "--seed") {
      o.seed = static_cast<std::uint64_t>(parseInt(a, value(), 0, 9007199254740991LL));
    } else if (a == "--frames") {
      o.frames = static_cast<int>(parseInt(a, value(), 1, 100000));
      frames_set = true;
    } else if (a == "--duration") {
      const double seconds = parseDouble(a, value(), 0.1, 10000.0);
      o.frames = std::max(1, static_cast<int>(std::lround(seconds * frame_rate_hz)));
      duration_set = true;
    } else if (a == "--people") {
      o.people = static_cast<int>(parseInt(a, value(), 0, 250));
    } else if (a == "--noise") {
      o.noise = oneOf(a, value(), {"clean", "realistic"});
    } else if (a == "--range-noise-m") {
      o.range_noise_m = parseDouble(a, value(), 0.0, 1.0);
    } else if (a == "--mask-edge-px") {
      o.mask_edge_px = static_cast<int>(parseInt(a, value(), 0, 20));
    } else if (a == "--mask-edge-sign") {
      o.mask_edge_sign = oneOf(a, value(), {"both", "grow", "shrink"});
    } else if (a == "--mask-erosion-part") {
      o.mask_erosion_part = oneOf(a, value(), {"all", "thin", "outline"});
    } else if (a == "--miss-rate") {
      o.miss_rate = parseDouble(a, value(), 0.0, 1.0);
    } else if (a == "--false-cluster-rate") {
      o.false_cluster_rate = parseDouble(a, value(), 0.0, 1.0);
    } else if (a == "--false-mask-rate") {
      o.false_mask_rate = parseDouble(a, value(), 0.0, 1.0);
    } else if (a == "--mask-style") {
      o.mask_style = oneOf(a, value(), {"ids", "binary"});
    } else if (a == "--image-encoding") {
      o.image_encoding = oneOf(a, value(), {"mono8", "mono16"});
    } else if (a == "--full-cloud") {
      o.full_cloud = true;
    } else if (a == "--raw") {
      o.raw = true;
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
    } else if (a == "--extrinsic-change-at") {
      o.extrinsic_change_at_s = parseDouble(a, value(), 0.0, 1e6);
    } else if (a == "--extrinsic-change") {
      parseExtrinsicChange(a, value(), o);
      change_given = true;
    } else if (a == "--empty-image-region") {
      o.empty_image_region = oneOf(a, value(), {"left", "centre", "right"});
    } else if (a == "--camera-time-offset") {
      o.camera_time_offset_s = parseDouble(a, value(), -0.5, 0.5);
    } else if (a == "--lidar-point-time") {
      o.lidar_point_time = true;
    } else if (a == "--lidar-stamp") {
      o.lidar_stamp = oneOf(a, value(), {"start", "end"});
    } else if (a == "--lidar-cut-azimuth") {
      o.lidar_cut_azimuth_deg = parseDouble(a, value(), -360.0, 360.0);
      cut_given = true;
    } else if (a == "--speed-profile") {
      o.speed_profile = oneOf(a, value(), {"steady", "field"});
    } else if (a == "--walking-fraction") {
      o.walking_fraction = parseDouble(a, value(), 0.0, 1.0);
    } else {
      throw UsageError("unknown argument '" + a + "' (see --help)");
    }
  }
  if (frames_set && duration_set) throw UsageError("give either --frames or --duration, not both");
  finish(o, change_given, cut_given, frame_rate_hz);
  return o;
}

syn::SyntheticConfig syntheticConfigFrom(const MakeSyntheticBagOptions& o) {
  syn::SyntheticConfig c;
  c.rig = syn::rigByName(o.rig);
  c.seed = o.seed;
  c.frames = o.frames;
  c.scene.people = o.people;
  c.noise = syn::NoiseConfig::preset(o.noise);
  if (o.range_noise_m >= 0) c.noise.range_sigma_m = o.range_noise_m;
  if (o.mask_edge_px >= 0) c.noise.mask_edge_px = o.mask_edge_px;
  c.noise.mask_edge_sign = syn::maskEdgeSignByName(o.mask_edge_sign);
  c.noise.mask_erosion_part = syn::maskErosionPartByName(o.mask_erosion_part);
  if (o.miss_rate >= 0) c.noise.miss_rate = o.miss_rate;
  if (o.false_cluster_rate >= 0) c.noise.false_cluster_rate = o.false_cluster_rate;
  if (o.false_mask_rate >= 0) c.noise.false_mask_rate = o.false_mask_rate;
  c.mask_style = o.mask_style == "binary" ? syn::MaskStyle::kBinary : syn::MaskStyle::kIds;
  c.image_depth = o.image_encoding == "mono16" ? syn::ImageDepth::kMono16 : syn::ImageDepth::kMono8;
  c.full_cloud = o.full_cloud;
  c.raw = o.raw;
  if (o.raw) c.image_depth = syn::ImageDepth::kMono16Radiometric;
  c.extrinsic_change.at_s = o.extrinsic_change_at_s;
  c.extrinsic_change.rotation_deg = o.extrinsic_change_rotation_deg;
  c.extrinsic_change.translation_cm = o.extrinsic_change_translation_cm;
  c.empty_image_region = syn::imageRegionByName(o.empty_image_region);
  c.timing.camera_time_offset_s = o.camera_time_offset_s;
  c.timing.lidar_stamp = syn::lidarStampByName(o.lidar_stamp);
  c.timing.lidar_point_time = o.lidar_point_time;
  c.timing.lidar_cut_azimuth_rad = o.lidar_cut_azimuth_deg * M_PI / 180.0;
  c.scene.speed_profile = syn::speedProfileByName(o.speed_profile);
  if (o.walking_fraction >= 0.0) c.scene.walking_fraction = o.walking_fraction;
  return c;
}

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
