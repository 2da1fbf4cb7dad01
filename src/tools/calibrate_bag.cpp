// calibrate_bag: parameters -> bag -> shared ingest path -> the calibration job (fit, quality,
// result file, report; the node runs the same job) -> summary.

#include "thermal_lidar_calibration/tools/calibrate_bag.hpp"
#include "thermal_lidar_calibration/ros/dataset_bag.hpp"

#include "thermal_lidar_calibration/ros/bag_ingest.hpp"
#include "thermal_lidar_calibration/app/files/writable_path.hpp"
#include "thermal_lidar_calibration/app/parameters/association_parameters.hpp"
#include "thermal_lidar_calibration/app/runtime/calibration_job.hpp"
#include "thermal_lidar_calibration/tools/calibration_summary.hpp"
#include "thermal_lidar_calibration/app/report/timing_text.hpp"
#include "thermal_lidar_calibration/tools/drift_timeline.hpp"
#include "thermal_lidar_calibration/app/files/camera_info_file.hpp"
#include "thermal_lidar_calibration/tools/progress_line.hpp"
#include "thermal_lidar_calibration/app/report/quality_output.hpp"
#include "thermal_lidar_calibration/app/files/result_file.hpp"
#include "thermal_lidar_calibration/app/parameters/unknown_parameters.hpp"
#include "thermal_lidar_calibration/app/parameters/parameter_catalog.hpp"

#include <opencv2/imgcodecs.hpp>

#include <algorithm>
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
      camera, inOfferOrder(builder.pairs(), builder.candidates()), reference, params.drift, params.calibration,
      [&](std::size_t done, std::size_t total) {
        progress.update("drift watch: pair " + std::to_string(done) + "/" + std::to_string(total));
        return !g_interrupted;
      },
      // The reference's own camera time offset (a result file of a run that applied one).
      params.calibration.time_offset.mode == TimeOffsetMode::kNone ? std::nullopt
                                                                   : readAppliedTimeOffset(options.reference),
      // Issue 23: the frames the count rule did not keep pair by association at the reference.
      associationIfAsked(params));
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
  std::printf("  pairs by rule    counts %llu, association %llu (of %llu frames the count rule did not keep)\n",
              static_cast<unsigned long long>(timeline.pairs - timeline.association_pairs),
              static_cast<unsigned long long>(timeline.association_pairs),
              static_cast<unsigned long long>(timeline.candidates));
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
  if (timeline.time_offset_s) {
    std::printf("  timing           %s: the reference's time offset %+.1f ms%s\n", toString(timeline.timing_state),
                1000.0 * *timeline.time_offset_s,
                timeline.timing_change_s
                    ? (" changed by " + std::to_string(static_cast<int>(std::lround(1000.0 * *timeline.timing_change_s))) +
                       " ms (a camera driver restarted with another latency?): the extrinsic fits at the new offset; "
                       "set time_offset_s to the new offset")
                          .c_str()
                    : " holds");
  }
  std::printf("  files            %s, %s, %s\n", options.output.c_str(), csv.c_str(), png.c_str());
  std::printf("  monitor time     %.2f s for %zu tests\n", timeline.seconds, timeline.records.size());
  std::fflush(stdout);
  return 0;
}

// Checked before the bag is read: a run must not end in "cannot write" after minutes of work.
void checkOutputsWritable(const CalibrateBagOptions& options) {
  const std::string output_problem = whyNotWritable(options.output);
  if (!output_problem.empty()) throw std::invalid_argument("--output: " + output_problem);
  if (options.report.empty()) return;
  std::error_code made;
  std::filesystem::create_directories(options.report, made);
  const std::string report_problem = made ? made.message() : whyNotWritable(options.report + "/index.html");
  if (!report_problem.empty()) throw std::invalid_argument("--report " + options.report + ": " + report_problem);
}

// The file's extrinsic, read before the bag (a typo must not cost the minutes of reading it);
// nullopt without a file. `flag` prefixes the error when not empty.
std::optional<Extrinsic> readOptionalExtrinsic(const std::string& path, const std::string& flag) {
  if (path.empty()) return std::nullopt;
  try {
    return readExtrinsicFile(path);
  } catch (const std::invalid_argument& e) {
    if (flag.empty()) throw;
    throw std::invalid_argument(flag + ": " + e.what());
  }
}

// A calibration_node dataset bag, read back as ~resume reads it (restoreDataset): pairs stay
// pairs, association candidates candidates at their place among the frames the node was offered.
BagIngestStats restoreFromDatasetBag(const std::string& path, DatasetBuilder& builder) {
  DatasetBagContents contents = readDatasetBag(path, false);
  BagIngestStats stats;
  stats.frames = contents.frames.size() + contents.errors.size();
  stats.messages_total = stats.messages_read = 3 * stats.frames;
  const RestoredDataset restored = restoreDataset(std::move(contents), builder);
  builder.flushPending();  // a stored pair without its motion gets none: no scans between them
  for (const std::string& error : restored.skipped) ++stats.bad_message_errors[error];
  if (restored.pairs == 0 && restored.candidates > 0) {
    stats.damage = "the dataset bag holds " + std::to_string(restored.candidates) +
                   " association candidates but no pair of the count rule, which the first fit needs: "
                   "resume the node (~resume) on more of the drive until it keeps frames whose counts agree";
  }
  return stats;
}

// What the bag gave: its camera, the kept pairs (in the builder) and how reading went.
struct BagPairs {
  CameraModel camera;
  std::unique_ptr<DatasetBuilder> builder;
  BagIngestStats stats;
};

// The bag through the shared ingest path (the node's FrameSynchronizer -> DatasetBuilder).
// Throws std::invalid_argument when it yields no pairs, saying why.
BagPairs readPairs(const CalibrateBagOptions& options, CoreParameters& params, ProgressLine& progress) {
  const BagTopics topics{options.image_topic, options.mask_topic, options.clusters_topic,
                         options.camera_info_topic, options.points_topic, options.detect};
  std::unique_ptr<PersonDetectionAdapter> detectors;
  if (options.detect) detectors = std::make_unique<PersonDetectionAdapter>(loadDetection(options));
  rosbag::Bag bag;
  openBag(bag, options.bag);
  const std::vector<BagTopicInfo> bag_topics = listBagTopics(bag);
  checkBagTopics(bag_topics, topics, options.bag);
  // A calibration_node dataset bag holds only frames the node already kept: they are read back as
  // ~resume reads them (restoreFromDatasetBag). Through the detectors they are offered as frames,
  // and the skip rule applied again would drop three of every four.
  const bool dataset_bag = std::any_of(bag_topics.begin(), bag_topics.end(),
                                       [](const BagTopicInfo& t) {
                                         return t.topic == DatasetBagTopics::kMarker ||
                                                t.topic == DatasetBagTopics::kCandidateMarker ||
                                                t.topic == DatasetBagTopics::kSkippedMarker;
                                       });
  if (dataset_bag && !options.quiet) {
    std::fprintf(stderr, "calibrate_bag: note: a calibration_node dataset bag: %s\n",
                 options.detect ? "its frames through the detectors, skip rule off"
                                : "its pairs and association candidates as the node kept them");
  }
  if (dataset_bag && options.detect) params.gate.skip_frames = 0;
  BagPairs read;
  read.camera = options.camera_info_file.empty() ? cameraModelFromBag(bag, topics.camera_info, bag_topics)
                                                 : loadCameraInfoFile(options.camera_info_file);
  if (!options.quiet) {
    std::fprintf(stderr, "calibrate_bag: camera %s; %s\n", read.camera.describe().c_str(),
                 algorithmText(params.calibration).c_str());
  }
  if (detectors) {
    const std::string window = lidarWindowWarning(detectors->parameters().lidar.person, read.camera);
    if (!window.empty()) warn(window);
  }

  read.builder = std::make_unique<DatasetBuilder>(read.camera, params.gate, params.motion);
  DatasetBuilder& builder = *read.builder;
  builder.keepAssociationCandidates(pairsByAssociation(params.pairing, params.calibration));
  // The drift watch (--monitor) pairs the spaced frames only, as the node's does.
  builder.keepSkippedFrames(params.pairing.final_round && !options.monitor);
  IngestCallbacks callbacks;
  callbacks.warn = warn;
  callbacks.progress = [&](const BagIngestStats& s, const DatasetBuilder& b) {
    progress.update("reading: " + std::to_string(s.messages_read) + "/" +
                    std::to_string(s.messages_total) + " messages, " + std::to_string(s.frames) +
                    " frames, " + std::to_string(b.pairs().size()) + " pairs kept");
    return !g_interrupted;
  };
  if (dataset_bag && !options.detect) {
    bag.close();
    read.stats = restoreFromDatasetBag(options.bag, builder);
  } else {
    read.stats = ingestBag(bag, topics, params, builder, callbacks, detectors.get());
  }
  const BagIngestStats& stats = read.stats;
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
  if (builder.pairs().empty() && dataset_bag && !options.detect) {
    throw std::invalid_argument("no pairs in the dataset bag " + options.bag + ": " +
                                (!stats.damage.empty() ? stats.damage
                                 : stats.bad_message_errors.empty()
                                     ? std::string("it holds no stored frame")
                                     : "its frames could not be read, e.g. " + stats.bad_message_errors.begin()->first));
  }
  if (builder.pairs().empty()) {
    throw std::invalid_argument(noPairsMessage(stats, builder.counts(), params, topics));
  }
  return read;
}

// The calibration job on the bag's pairs (the node runs the same job), with its progress on
// stderr. Throws when the fit failed or a file asked for could not be written.
CalibrationJobOutcome calibratePairs(const CalibrateBagOptions& options, const CoreParameters& params,
                                     BagPairs& read, const std::optional<Extrinsic>& truth,
                                     const std::optional<Extrinsic>& reference,
                                     const std::optional<InitialExtrinsic>& initial, ProgressLine& progress) {
  CalibrationJobRequest job;
  job.camera = read.camera;
  job.pairs = read.builder->takePairs();
  job.candidates_collected = read.builder->keepsAssociationCandidates();
  job.candidates = inOfferOrder(read.builder->takeCandidates(), read.builder->takeSkippedFrames());
  job.initial = initial;
  job.parameters = params;
  if (reference) job.reference = JobReference{*reference, "file", options.reference};
  if (truth) {
    bool point_times = false;
    for (const CalibrationPair& pair : job.pairs) point_times = point_times || !pair.point_time_s.empty();
    job.truth = JobTruth{*truth, options.truth, readTimeOffset(options.truth, point_times)};
  }
  job.lidar_frame = read.builder->lidarFrame();
  job.camera_frame = read.builder->cameraFrame();
  job.source = options.bag;
  job.report_title = "calibrate_bag " + options.bag;
  job.output_file = options.output;
  job.report_dir = options.report;
  job.write_stopped_result = true;  // Ctrl-C keeps the best result so far
  const std::size_t pairs = job.pairs.size();
  const std::size_t frames = read.stats.frames;
  const int resamples = params.quality.uncertainty.resamples;
  JobProgress::Stage stage = JobProgress::Stage::kFit;
  CalibrationJobOutcome outcome = runCalibrationJob(job, [&](const JobProgress& p) {
    if (p.stage != stage) progress.finish();  // each stage on a line of its own
    stage = p.stage;
    char buf[256];
    if (p.stage == JobProgress::Stage::kFit) {
      std::snprintf(buf, sizeof(buf),
                    "optimizing: %zu pairs kept of %zu frames | %s generation %d/%d | best loss %.4f px",
                    pairs, frames, p.fit.stage.c_str(), p.fit.generation, p.fit.generations_total,
                    p.fit.best_loss);
      progress.update(buf);
    } else if (p.stage == JobProgress::Stage::kUncertainty) {
      std::snprintf(buf, sizeof(buf), "uncertainty: bootstrap resample %d/%d", p.resample, resamples);
      progress.update(buf);
    }
    return !g_interrupted;
  });
  progress.finish();
  if (!outcome.result) {
    throw std::invalid_argument("cannot calibrate on " + std::to_string(pairs) + " pairs: " + outcome.error);
  }
  if (!outcome.quality_error.empty()) warn(outcome.quality_error);
  const std::string late = timeOffsetWarning(*outcome.result);
  if (!late.empty()) warn(late);
  if (!outcome.result_file_written) throw std::runtime_error(outcome.result_file_error);
  if (!options.report.empty()) {
    if (!outcome.report_error.empty()) throw std::runtime_error(outcome.report_error);
    if (!options.quiet) {
      std::printf("report: %s/index.html (%zu files)\n", options.report.c_str(), outcome.report_files.size());
    }
  }
  return outcome;
}

}  // namespace

int runCalibrateBag(const CalibrateBagOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  g_interrupted = false;
  std::signal(SIGINT, onSigint);

  CoreParameters params = loadParameters(options);
  checkOutputsWritable(options);
  const std::optional<Extrinsic> truth = readOptionalExtrinsic(options.truth, "");
  const std::optional<Extrinsic> reference = readOptionalExtrinsic(options.reference, "--reference");
  // Read before the bag, as the other files: a typo must not cost the minutes of reading it.
  std::optional<InitialExtrinsic> initial;
  if (!params.initial_extrinsic_file.empty()) initial = readInitialExtrinsic(params.initial_extrinsic_file);

  ProgressLine progress(stderr, !options.quiet);
  BagPairs read = readPairs(options, params, progress);
  if (options.monitor) {
    return runDriftWatch(options, params, read.camera, *read.builder, *reference, progress);
  }
  const CalibrationJobOutcome outcome = calibratePairs(options, params, read, truth, reference, initial, progress);
  const CalibrationResult& result = *outcome.result;

  SummaryInput summary;
  summary.bag_path = options.bag;
  summary.output_path = options.output;
  summary.lidar_frame = outcome.context.lidar_frame;
  summary.camera_frame = outcome.context.camera_frame;
  summary.algorithm_text = algorithmText(params.calibration);
  summary.messages_read = read.stats.messages_read;
  summary.frames = read.stats.frames;
  summary.counts = read.builder->counts();
  summary.result = result;
  summary.truth = outcome.context.truth;
  summary.quality = outcome.quality;
  summary.pairing = outcome.pairing;
  summary.total_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!options.quiet || result.stopped) {
    std::fputs(formatCalibrationSummary(summary).c_str(), stdout);
    std::fflush(stdout);
  }
  if (result.stopped) {
    throw std::runtime_error("interrupted; the best result so far was written to " + options.output);
  }
  return 0;
}

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
