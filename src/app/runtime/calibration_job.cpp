// The calibration job both front ends run: fit -> quality -> truth -> result file -> report.

#include "thermal_lidar_calibration/app/runtime/calibration_job.hpp"

#include "thermal_lidar_calibration/app/parameters/association_parameters.hpp"
#include "thermal_lidar_calibration/app/report/calibration_report.hpp"
#include "thermal_lidar_calibration/core/loss.hpp"
#include "thermal_lidar_calibration/core/pose_difference.hpp"

#include <exception>
#include <utility>

namespace thermal_lidar_calibration {
namespace {

// How far to trust the fit: bootstrap intervals, coverage, verdict, the reference's standing.
// The bootstrap draws from the calibration's seed, uses its threads and its time offset range,
// so one seed gives one answer in both front ends.
void assess(const CalibrationJobRequest& request, const std::vector<CalibrationPair>& pairs,
            const JobCallback& callback, CalibrationJobOutcome& out) {
  const CalibrationConfig& calibration = request.parameters.calibration;
  QualityConfig config = request.parameters.quality;
  config.uncertainty.seed = calibration.seed;
  config.uncertainty.num_threads = calibration.num_threads;
  config.time_offset = calibration.time_offset;
  config.ring_end_weight = calibration.refine.ring_end_weight;
  std::optional<Extrinsic> reference;
  if (request.reference) reference = request.reference->extrinsic;
  try {
    out.quality = assessQuality(request.camera, pairs, *out.result, config,
                                calibration.behind_camera_penalty_c1, reference,
                                [&](int done, int total) {
                                  if (!callback) return true;
                                  JobProgress p;
                                  p.stage = JobProgress::Stage::kUncertainty;
                                  p.resample = done;
                                  p.resamples = total;
                                  return callback(p);
                                });
  } catch (const std::exception& e) {
    out.quality_error = std::string("quality assessment failed: ") + e.what();
    return;
  }
  if (out.quality->reference && request.reference) {
    out.quality->reference->source = request.reference->source;
    out.quality->reference->origin = request.reference->origin;
  }
}

// The result against the known truth, and the truth's own loss on the pairs the result used.
TruthComparison compareWithTruth(const CalibrationJobRequest& request, const std::vector<CalibrationPair>& pairs,
                                 const CalibrationResult& result) {
  TruthComparison cmp;
  cmp.truth_file = request.truth->file;
  cmp.rotation_error_rad = rotationErrorRad(result.extrinsic, request.truth->extrinsic);
  cmp.translation_error_m = translationErrorM(result.extrinsic, request.truth->extrinsic);
  LossConfig loss_config;
  loss_config.behind_camera_penalty_c1 = request.parameters.calibration.behind_camera_penalty_c1;
  loss_config.pixel_rule = PixelRule::kNearest;
  if (result.time_offset_mode != TimeOffsetMode::kNone) {
    loss_config.time_offset_s = request.truth->time_offset_s.value_or(result.time_offset_s);
  }
  const LossEvaluator evaluator(request.camera, pairs, loss_config);
  cmp.truth_loss = evaluator.loss(request.truth->extrinsic, usedPairs(result));
  return cmp;
}

void writeReport(const CalibrationJobRequest& request, CalibrationJobOutcome& out) {
  ReportInput report;
  report.camera = &request.camera;
  report.pairs = &out.fitted_pairs;
  report.result = &*out.result;
  report.quality = out.quality ? &*out.quality : nullptr;
  report.threshold_px = request.parameters.calibration.outlier.threshold_px;
  report.source = request.report_title;
  report.lidar_frame = out.context.lidar_frame;
  report.camera_frame = out.context.camera_frame;
  try {
    out.report_files = writeCalibrationReport(request.report_dir, report);
  } catch (const std::exception& e) {
    out.report_error = e.what();
  }
}

// The initial extrinsic the request gives, or the one its parameters name (read here so that both
// front ends honour the key); nullopt without either.
std::optional<InitialExtrinsic> initialExtrinsic(const CalibrationJobRequest& request) {
  if (request.initial) return request.initial;
  const std::string& path = request.parameters.initial_extrinsic_file;
  if (path.empty()) return std::nullopt;
  return readInitialExtrinsic(path);
}

// The first fit on the count rule's pairs, then (pairing association) the association rounds.
AssociatedCalibration fit(const CalibrationJobRequest& request, const JobCallback& callback) {
  const CoreParameters& p = request.parameters;
  const AssociationPairing association = associationPairing(p);
  PairingConfig pairing = p.pairing;
  pairing.association = association.config;
  return calibrateWithAssociation(request.camera, request.pairs, request.candidates, p.calibration, pairing,
                                  association.limits, initialExtrinsic(request),
                                  [&](const Progress& progress) {
                                    if (!callback) return true;
                                    JobProgress job;
                                    job.fit = progress;
                                    return callback(job);
                                  });
}

PairingSummary summarise(const CalibrationJobRequest& request, const AssociatedCalibration& fitted) {
  PairingSummary s;
  const bool asked = pairsByAssociation(request.parameters.pairing, request.parameters.calibration);
  const bool associate = asked && request.candidates_collected;
  s.mode = associate ? PairingMode::kAssociation : PairingMode::kCounts;
  s.counts = fitted.counts_pairs;
  s.association = fitted.association_pairs;
  for (const CalibrationPair& c : request.candidates) {
    if (!associate) break;
    (c.outside_skip_rule ? s.skipped_frames : s.candidates) += 1;
  }
  s.final_round = fitted.final_round;
  s.final_round_pairs = fitted.final_round_pairs;
  s.rounds = fitted.rounds;
  s.converged = fitted.converged;
  s.initial_used = fitted.initial_used;
  s.note = fitted.note;
  if (asked && !associate) {
    s.note += std::string(s.note.empty() ? "" : "; ") +
              "pairing association not applied: this front end kept no frames for it";
  }
  return s;
}

}  // namespace

InitialExtrinsic readInitialExtrinsic(const std::string& path) {
  try {
    InitialExtrinsic initial;
    initial.extrinsic = readExtrinsicFile(path);
    initial.time_offset_s = readAppliedTimeOffset(path);
    initial.origin = path;
    return initial;
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("initial_extrinsic_file: ") + e.what());
  }
}

std::string saveResultFile(const std::string& path, const CalibrationResult& result,
                           const ResultContext& context) {
  try {
    writeResultFile(path, result, context);
    checkExtrinsicFile(path, result.extrinsic);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

CalibrationJobOutcome runCalibrationJob(const CalibrationJobRequest& request,
                                        const JobCallback& callback) {
  CalibrationJobOutcome out;
  out.pairs = request.pairs.size();
  try {
    AssociatedCalibration fitted = fit(request, callback);
    out.result = std::move(fitted.result);
    out.pairing = summarise(request, fitted);
    out.fitted_pairs = std::move(fitted.pairs);
  } catch (const std::exception& e) {
    out.error = e.what();
    return out;
  }
  out.pairs = out.fitted_pairs.size();
  const CalibrationResult& result = *out.result;
  if (!result.stopped) assess(request, out.fitted_pairs, callback, out);

  ResultContext& context = out.context;
  context.lidar_frame = request.lidar_frame.empty() ? "lidar" : request.lidar_frame;
  context.camera_frame = request.camera_frame.empty() ? "camera" : request.camera_frame;
  context.source = request.source;
  context.parameters = request.parameters;
  context.quality = out.quality;
  context.pairing = out.pairing;
  context.pair_stamps_s.reserve(out.fitted_pairs.size());
  for (const CalibrationPair& pair : out.fitted_pairs) {
    context.pair_stamps_s.push_back(pair.stamp_s);
    context.pair_rules.push_back(pair.rule);
  }
  if (request.truth) context.truth = compareWithTruth(request, out.fitted_pairs, result);

  if (result.stopped && !request.write_stopped_result) return out;
  // The last chance to stop before anything reaches the disk (the node's ~reset during the
  // bootstrap); a front end that keeps stopped work writes it anyway.
  if (callback && !request.write_stopped_result) {
    JobProgress writing;
    writing.stage = JobProgress::Stage::kWriting;
    if (!callback(writing)) return out;
  }
  if (!request.output_file.empty()) {
    out.result_file_error = saveResultFile(request.output_file, result, context);
    out.result_file_written = out.result_file_error.empty();
  }
  if (!request.report_dir.empty()) writeReport(request, out);
  return out;
}

}  // namespace thermal_lidar_calibration
