#include "thermal_lidar_calibration/tools/make_synthetic_bag.hpp"

#include "thermal_lidar_calibration/core/frame_gate.hpp"
#include "thermal_lidar_calibration/ros/synthetic_bag_writer.hpp"
#include "thermal_lidar_calibration/tools/synthetic_truth_file.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

namespace thermal_lidar_calibration {
namespace ros_io {
namespace {

namespace syn = synthetic;

// What the consumer's gate will make of the drive, with the default gate settings.
void printSummary(const syn::SyntheticRig& rig, const std::vector<PeopleCounts>& counts) {
  const syn::SyntheticConfig& c = rig.config();
  const GateConfig gate;  // the defaults calibrate_bag and the node start from
  GateConfig no_skip = gate;
  no_skip.skip_frames = 0;
  const auto kept = [&](const GateConfig& g) {
    return static_cast<unsigned long long>(syn::gateFrames(counts, g)[GateDecision::kKept]);
  };
  std::printf("rig %s, seed %llu, %d frames, %zu people; frames with equal mask/cluster counts in 1..%d: %llu; "
              "pairs under the default gate (skip %d): %llu\n",
              c.rig.name.c_str(), static_cast<unsigned long long>(c.seed), c.frames, rig.scene().people().size(),
              gate.max_people, kept(no_skip), gate.skip_frames, kept(gate));
  const syn::ExtrinsicChange& change = rig.extrinsicChange();
  if (change.enabled) {
    const auto split = counts.begin() + std::min<std::ptrdiff_t>(change.first_frame, counts.size());
    const auto keptIn = [&](std::vector<PeopleCounts> part) {
      return static_cast<unsigned long long>(syn::gateFrames(part, gate)[GateDecision::kKept]);
    };
    std::printf("extrinsic change at %.3f s (stamp %.3f, frame %d): %.3f deg, %.2f cm; pairs under the default "
                "gate before / after it: %llu / %llu\n",
                change.at_s, change.at_stamp_s, change.first_frame, change.rotation_deg, change.translation_cm,
                keptIn({counts.begin(), split}), keptIn({split, counts.end()}));
  }
  const syn::ColumnRange empty = rig.emptyColumns();
  if (empty.end > empty.begin) {
    std::printf("empty image region %s: columns %d..%d hold no person\n", syn::toString(c.empty_image_region),
                empty.begin, empty.end - 1);
  }
  if (c.timing.camera_time_offset_s != 0.0) {
    std::printf("the images show the world %.3f s after their stamps (time_offset_s)\n", c.timing.camera_time_offset_s);
  }
  if (const syn::LidarSweep* sweep = rig.sweep()) {
    std::printf("the LiDAR sweeps from %.3f to %.3f s around its stamp (%s)%s\n", sweep->firstPointFromStamp(),
                sweep->lastPointFromStamp(), syn::toString(c.timing.lidar_stamp),
                c.timing.lidar_point_time ? ", with a per-point time field" : "");
  }
  if (c.scene.speed_profile != syn::SpeedProfile::kSteady) {
    std::printf("speed profile %s: 0 to %.1f m/s\n", syn::toString(c.scene.speed_profile),
                rig.scene().schedule().maxSpeed());
  }
}

}  // namespace

int runMakeSyntheticBag(const MakeSyntheticBagOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  const syn::SyntheticRig rig(syntheticConfigFrom(o));  // throws std::invalid_argument on bad settings
  const syn::SyntheticConfig& c = rig.config();

  SyntheticBagSettings settings;
  settings.lidar_frame = o.lidar_frame;
  settings.camera_frame = o.camera_frame;
  settings.camera_parent = o.camera_parent;
  settings.camera_info = o.camera_info;
  settings.time_jitter_s = o.time_jitter_s;
  SyntheticBagWriter writer(o.output, settings, c);

  std::vector<PeopleCounts> counts;
  // Frames are rendered in parallel (each depends only on the seed and its index) and written in
  // order; a batch bounds the memory held.
  constexpr int kBatch = 32;
  std::vector<syn::SyntheticFrame> batch;
  for (int first = 0; first < c.frames; first += kBatch) {
    const int n = std::min(kBatch, c.frames - first);
    batch.assign(static_cast<std::size_t>(n), syn::SyntheticFrame{});
#pragma omp parallel for schedule(dynamic)
    for (int k = 0; k < n; ++k) batch[static_cast<std::size_t>(k)] = rig.render(first + k);
    for (const auto& frame : batch) {
      writer.write(frame);
      counts.push_back(frame.counts);
    }
    std::fprintf(stderr, "\rmake_synthetic_bag: %d/%d frames", first + n, c.frames);
  }
  writer.close();
  std::fprintf(stderr, "\n");
  writeSyntheticTruth(o, rig);

  struct stat st {};
  const double size_mb = ::stat(o.output.c_str(), &st) == 0 ? st.st_size / 1e6 : 0.0;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("wrote %s (%.1f MB) and %s in %.1f s\n", o.output.c_str(), size_mb, o.truth.c_str(), seconds);
  printSummary(rig, counts);
  return 0;
}

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
