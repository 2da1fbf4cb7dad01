// calibrate_bag: parameters -> bag -> shared ingest path -> calibrate() -> result file + summary.

#include "thermal_lidar_calibration/tools/calibrate_bag.hpp"
#include "thermal_lidar_calibration/ros/dataset_bag.hpp"

#include "thermal_lidar_calibration/core/loss.hpp"
#include "thermal_lidar_calibration/ros/bag_ingest.hpp"
#include "thermal_lidar_calibration/app/writable_path.hpp"
#include "thermal_lidar_calibration/app/calibration_summary.hpp"
#include "thermal_lidar_calibration/app/calibration_report.hpp"
#include "thermal_lidar_calibration/app/drift_timeline.hpp"
#include "thermal_lidar_calibration/app/camera_info_file.hpp"
#include "thermal_lidar_calibration/app/progress_line.hpp"
#include "thermal_lidar_calibration/app/quality_output.hpp"
#include "thermal_lidar_calibration/app/result_file.hpp"
#include "thermal_lidar_calibration/app/unknown_parameters.hpp"
#include "thermal_lidar_calibration/node/parameter_catalog.hpp"

#include <opencv2/imgcodecs.hpp>

#include <atomic>
#include <memory>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

namespace thermal_lidar_calibration {
namespace ros_io {
namespace {

std::atomic<bool> g_interrupted{false};

extern "C" void onSigint(int) { g_interrupted = true; }

void warn(const std::string& text) {
  std::fprintf(stderr, "calibrate_bag: warning: %s\n", text.c_str());
}

std::string joined(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& s : items) out += (out.empty() ? "" : ", ") + s;
  return out;
}

CoreParameters loadParameters(const CalibrateBagOptions& options) {
  CoreParameters params;
  if (!options.config.empty()) {
    try {
      const std::vector<std::string> unknown = unknownParameterKeys(yamlFileKeys(options.config), knownParameterKeys());
      if (!unknown.empty()) {
        warn("--config " + options.config + ": unknown keys ignored (possible typo): " +
             joined(unknown));
      }
      params = loadCoreParameters(*makeYamlParameterSource(options.config));
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("--config " + options.config + ": " + e.what());
    }
  }
  CalibrationConfig& c = params.calibration;
  if (options.algorithm) {
    c.algorithm = *options.algorithm == 1 ? Algorithm::kPlain : Algorithm::kOutlierRejection;
  }
  if (options.refine) c.refine.mode = *options.refine == "none" ? RefineMode::kNone : RefineMode::kLocal;
  if (options.seed) c.seed = *options.seed;
  if (options.threads) c.num_threads = *options.threads;
  c.validate();
  return params;
}

// The detectors' keys of --config (the same keys the detection nodelets read).
DetectionParameters loadDetection(const CalibrateBagOptions& options) {
  if (options.config.empty()) return DetectionParameters{};
  try {
    return loadDetectionParameters(*makeYamlParameterSource(options.config));
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("--config " + options.config + ": " + e.what());
  }
}

std::string algorithmText(const CalibrationConfig& c) {
  return std::string("Algorithm ") + (c.algorithm == Algorithm::kPlain ? "1" : "2") +
         ", refine " + (c.refine.mode == RefineMode::kNone ? "none" : "local") + ", seed " +
         std::to_string(c.seed);
}

std::string noPairsMessage(const BagIngestStats& stats, const RejectionCounts& counts,
                           const CoreParameters& params, const BagTopics& topics) {
  if (stats.frames == 0) {
    char slop[32];
    std::snprintf(slop, sizeof(slop), "%g", params.sync_slop_s);
    return "no synchronized frames: read " + std::to_string(stats.messages_read) +
           " messages on " + topics.image + ", " +
           (topics.detect ? topics.points : topics.mask + ", " + topics.clusters) +
           " but none matched within sync_slop = " + slop +
           " s; check the header stamps or raise sync_slop in --config" +
           (stats.damage.empty() ? "" : "; " + stats.damage);
  }
  std::string msg = "no pairs kept from " + std::to_string(stats.frames) +
                    " synchronized frames (" + counts.summary() + ")";
  if (!stats.bad_message_errors.empty()) {
    std::uint64_t bad = 0;
    for (const auto& kv : stats.bad_message_errors) bad += kv.second;
    msg += "; " + std::to_string(bad) + " bad frames, e.g. " +
           stats.bad_message_errors.begin()->first;
  } else if (topics.detect) {
    msg += "; the detectors never saw the same number of people in the image and the cloud: "
           "try detect_people on a frame of each (radiometric scale kelvin_per_count, "
           "thermal_input_flip, lidar_max_range_m)";
  } else {
    msg += "; check that masks and clusters see the same people";
  }
  if (!stats.damage.empty()) msg += "; " + stats.damage;
  return msg;
}

std::vector<std::size_t> inlierIndices(const CalibrationResult& result) {
  std::vector<std::size_t> used;
  for (std::size_t i = 0; i < result.inliers.size(); ++i) {
    if (result.inliers[i]) used.push_back(i);
  }
  return used;
}

// "OUT.drift.csv" beside "OUT.yaml".
std::string besideOutput(const std::string& output, const std::string& suffix) {
  const std::size_t dot = output.rfind('.');
  const std::size_t slash = output.rfind('/');
  const bool has_ext = dot != std::string::npos && (slash == std::string::npos || dot > slash);
  return (has_ext ? output.substr(0, dot) : output) + suffix;
}

// --monitor: the kept pairs, in time order, through the drift watch against --reference.
int runDriftWatch(const CalibrateBagOptions& options, const CoreParameters& params,
                  const CameraModel& camera, const DatasetBuilder& builder, const Extrinsic& reference,
                  ProgressLine& progress) {
  const DriftTimeline timeline = watchDrift(
      camera, builder.pairs(), reference, params.drift, params.calibration,
      [&](std::size_t done, std::size_t total) {
        progress.update("drift watch: pair " + std::to_string(done) + "/" + std::to_string(total));
        return !g_interrupted;
      });
  progress.finish();
  const std::string lidar = builder.lidarFrame().empty() ? "lidar" : builder.lidarFrame();
  const std::string cam = builder.cameraFrame().empty() ? "camera" : builder.cameraFrame();
  const std::string csv = besideOutput(options.output, ".drift.csv");
  const std::string png = besideOutput(options.output, ".drift.png");
  writeDriftResult(options.output, timeline, lidar, cam, options.reference);
  writeDriftCsv(csv, timeline);
  if (!cv::imwrite(png, drawDriftPlot(timeline))) throw std::runtime_error("cannot write " + png);
  const auto stamp = [](const std::optional<double>& s) {
    char text[32];
    std::snprintf(text, sizeof(text), "%.1f", s ? *s : 0.0);
    return s ? std::string(text) : std::string("never");
  };
  const DriftChange change = timeline.candidate ? timeline.candidate->change
                             : timeline.records.empty() ? DriftChange{}
                                                        : timeline.records.back().test.change;
  char line[256];
  std::snprintf(line, sizeof(line), "%.3f deg, [%.2f, %.2f, %.2f] cm", change.angle_deg,
                change.translation_cm.x(), change.translation_cm.y(), change.translation_cm.z());
  std::printf("thermal_lidar_calibration drift watch (%s)\n", options.bag.c_str());
  std::printf("  pairs            %llu kept, %zu tests of the latest %d pairs every %d\n",
              static_cast<unsigned long long>(timeline.pairs), timeline.records.size(),
              params.drift.window_pairs, params.drift.period_pairs);
  std::printf("  state            %s at the end; first WARN %s, first ERROR %s\n", toString(timeline.state),
              stamp(timeline.first_warn_stamp_s).c_str(), stamp(timeline.first_error_stamp_s).c_str());
  std::printf("  change           %s against %s%s\n", line, options.reference.c_str(),
              timeline.candidate ? " (the new extrinsic, fitted on the pairs since the change)" : " (latest window)");
  if (timeline.candidate) {
    const DriftCandidate& c = *timeline.candidate;
    std::printf("  new fit          %s, on %zu pairs since the change%s\n", toString(c.model), c.pairs,
                c.complete ? "" : " (not final: fewer than monitor_update_pairs)");
    if (c.uncertainty) {
      std::printf("  95 %% intervals   %s about / along camera x, y, z (what the pairs pin down)\n",
                  formatHalfWidths(*c.uncertainty).c_str());
    }
  }
  std::printf("  files            %s, %s, %s\n", options.output.c_str(), csv.c_str(), png.c_str());
  std::printf("  monitor time     %.2f s for %zu tests\n", timeline.seconds, timeline.records.size());
  std::fflush(stdout);
  return 0;
}

}  // namespace

int runCalibrateBag(const CalibrateBagOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  g_interrupted = false;
  std::signal(SIGINT, onSigint);

  CoreParameters params = loadParameters(options);
  // Checked before the bag is read: a run must not end in "cannot write" after minutes of work.
  const std::string output_problem = whyNotWritable(options.output);
  if (!output_problem.empty()) throw std::invalid_argument("--output: " + output_problem);
  if (!options.report.empty()) {
    std::error_code made;
    std::filesystem::create_directories(options.report, made);
    const std::string report_problem =
        made ? made.message() : whyNotWritable(options.report + "/index.html");
    if (!report_problem.empty()) {
      throw std::invalid_argument("--report " + options.report + ": " + report_problem);
    }
  }
  std::optional<Extrinsic> truth;
  if (!options.truth.empty()) truth = readExtrinsicFile(options.truth);
  std::optional<Extrinsic> reference;
  if (!options.reference.empty()) {
    try {
      reference = readExtrinsicFile(options.reference);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("--reference: ") + e.what());
    }
  }

  BagTopics topics{options.image_topic, options.mask_topic, options.clusters_topic,
                   options.camera_info_topic, options.points_topic, options.detect};
  std::unique_ptr<PersonDetectionAdapter> detectors;
  if (options.detect) detectors = std::make_unique<PersonDetectionAdapter>(loadDetection(options));
  rosbag::Bag bag;
  openBag(bag, options.bag);
  const std::vector<BagTopicInfo> bag_topics = listBagTopics(bag);
  checkBagTopics(bag_topics, topics, options.bag);
  // A calibration_node dataset bag holds only frames the node already kept: the skip rule
  // applied again would drop three of every four.
  for (const BagTopicInfo& t : bag_topics) {
    if (t.topic == DatasetBagTopics::kMarker && params.gate.skip_frames != 0) {
      params.gate.skip_frames = 0;
      if (!options.quiet) {
        std::fprintf(stderr,
                     "calibrate_bag: note: a calibration_node dataset bag (already gated): "
                     "skip rule off\n");
      }
    }
  }
  const CameraModel camera = options.camera_info_file.empty()
                                 ? cameraModelFromBag(bag, topics.camera_info, bag_topics)
                                 : loadCameraInfoFile(options.camera_info_file);
  if (!options.quiet) {
    std::fprintf(stderr, "calibrate_bag: camera %s; %s\n", camera.describe().c_str(),
                 algorithmText(params.calibration).c_str());
  }

  if (detectors) {
    const std::string window = lidarWindowWarning(detectors->parameters().lidar.person, camera);
    if (!window.empty()) warn(window);
  }

  ProgressLine progress(stderr, !options.quiet);
  DatasetBuilder builder(camera, params.gate);
  IngestCallbacks callbacks;
  callbacks.warn = warn;
  callbacks.progress = [&](const BagIngestStats& s, const DatasetBuilder& b) {
    progress.update("reading: " + std::to_string(s.messages_read) + "/" +
                    std::to_string(s.messages_total) + " messages, " + std::to_string(s.frames) +
                    " frames, " + std::to_string(b.pairs().size()) + " pairs kept");
    return !g_interrupted;
  };
  const BagIngestStats stats = ingestBag(bag, topics, params, builder, callbacks, detectors.get());
  bag.close();
  progress.update("read: " + std::to_string(stats.messages_read) + " messages, " +
                      std::to_string(stats.frames) + " frames, " +
                      std::to_string(builder.pairs().size()) + " pairs kept",
                  true);
  progress.finish();
  if (stats.interrupted) throw std::runtime_error("interrupted while reading the bag");
  if (!stats.damage.empty() && !builder.pairs().empty()) warn(stats.damage + "; using what was read");
  if (stats.undecodable_messages > 0) {
    warn(std::to_string(stats.undecodable_messages) + " messages could not be deserialised");
  }
  if (builder.pairs().empty()) {
    throw std::invalid_argument(noPairsMessage(stats, builder.counts(), params, topics));
  }

  if (options.monitor) {
    return runDriftWatch(options, params, camera, builder, *reference, progress);
  }

  const std::size_t frames = stats.frames;
  const ProgressCallback on_progress = [&](const Progress& p) {
    char buf[256];
    std::snprintf(buf, sizeof(buf),
                  "optimizing: %zu pairs kept of %zu frames | %s generation %d/%d | best loss %.4f px",
                  builder.pairs().size(), frames, p.stage.c_str(), p.generation,
                  p.generations_total, p.best_loss);
    progress.update(buf);
    return !g_interrupted;
  };
  CalibrationResult result;
  try {
    result = calibrate(camera, builder.pairs(), params.calibration, on_progress);
  } catch (const std::invalid_argument& e) {
    progress.finish();
    throw std::invalid_argument(std::string("cannot calibrate on ") +
                                std::to_string(builder.pairs().size()) + " pairs: " + e.what());
  }
  progress.finish();

  // How far to trust it: bootstrap intervals, coverage, verdict, and the reference's standing.
  std::optional<QualityAssessment> quality;
  if (!result.stopped) {
    QualityConfig quality_config = params.quality;
    quality_config.uncertainty.seed = params.calibration.seed;
    quality_config.uncertainty.num_threads = params.calibration.num_threads;
    const int total = quality_config.uncertainty.resamples;
    quality = assessQuality(camera, builder.pairs(), result, quality_config,
                            params.calibration.behind_camera_penalty_c1, reference,
                            [&](int done, int) {
                              progress.update("uncertainty: bootstrap resample " + std::to_string(done) +
                                              "/" + std::to_string(total));
                              return !g_interrupted;
                            });
    progress.finish();
    if (quality->reference) {
      quality->reference->source = "file";
      quality->reference->origin = options.reference;
    }
  }

  ResultContext context;
  context.quality = quality;
  context.lidar_frame = builder.lidarFrame().empty() ? "lidar" : builder.lidarFrame();
  context.camera_frame = builder.cameraFrame().empty() ? "camera" : builder.cameraFrame();
  context.source = options.bag;
  for (const auto& pair : builder.pairs()) context.pair_stamps_s.push_back(pair.stamp_s);
  context.parameters = params;
  if (truth) {
    TruthComparison cmp;
    cmp.truth_file = options.truth;
    cmp.rotation_error_rad = rotationErrorRad(result.extrinsic, *truth);
    cmp.translation_error_m = translationErrorM(result.extrinsic, *truth);
    LossConfig loss_config;
    loss_config.behind_camera_penalty_c1 = params.calibration.behind_camera_penalty_c1;
    loss_config.pixel_rule = PixelRule::kNearest;
    const LossEvaluator evaluator(camera, builder.pairs(), loss_config);
    cmp.truth_loss = evaluator.loss(*truth, inlierIndices(result));
    context.truth = cmp;
  }
  writeResultFile(options.output, result, context);
  if (!options.report.empty()) {
    ReportInput report;
    report.camera = &camera;
    report.pairs = &builder.pairs();
    report.result = &result;
    report.quality = quality ? &*quality : nullptr;
    report.threshold_px = params.calibration.outlier.threshold_px;
    report.source = "calibrate_bag " + options.bag;
    report.lidar_frame = context.lidar_frame;
    report.camera_frame = context.camera_frame;
    const std::vector<std::string> files = writeCalibrationReport(options.report, report);
    if (!options.quiet) std::printf("report: %s/index.html (%zu files)\n", options.report.c_str(), files.size());
  }

  SummaryInput summary;
  summary.bag_path = options.bag;
  summary.output_path = options.output;
  summary.lidar_frame = context.lidar_frame;
  summary.camera_frame = context.camera_frame;
  summary.algorithm_text = algorithmText(params.calibration);
  summary.messages_read = stats.messages_read;
  summary.frames = stats.frames;
  summary.counts = builder.counts();
  summary.result = result;
  summary.truth = context.truth;
  summary.quality = quality;
  summary.total_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!options.quiet || result.stopped) {
    std::fputs(formatCalibrationSummary(summary).c_str(), stdout);
    std::fflush(stdout);
  }
  if (result.stopped) {
    throw std::runtime_error("interrupted; the best result so far was written to " +
                             options.output);
  }
  return 0;
}

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
