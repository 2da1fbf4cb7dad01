#pragma once
// One calibration job for both front ends (robot_cal_tools' problem in, result out): the kept
// pairs and the configuration in; the fit, how far to trust it (intervals, coverage, verdict,
// the reference's standing), the truth comparison, the result file and the report out.
// calibrate_bag calls runCalibrationJob() directly; calibration_node runs it on its
// CalibrationWorker. A change to what follows the fit is made here, once. ROS-free: it never
// logs; progress leaves through a callback that can also ask it to stop.

#include "thermal_lidar_calibration/app/parameters/core_parameters.hpp"
#include "thermal_lidar_calibration/app/files/result_file.hpp"
#include "thermal_lidar_calibration/core/association_refit.hpp"
#include "thermal_lidar_calibration/core/calibration_pair.hpp"
#include "thermal_lidar_calibration/core/calibrator.hpp"
#include "thermal_lidar_calibration/core/camera_model.hpp"
#include "thermal_lidar_calibration/core/quality_assessment.hpp"

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace thermal_lidar_calibration {

// A transform the user already has, to compare the result with (result YAML `reference:`).
struct JobReference {
  Extrinsic extrinsic;
  std::string source;  // "file" | "tf"
  std::string origin;  // the file's path, or "tf velodyne -> thermal_optical"
};

// The known truth of a synthetic drive (calibrate_bag --truth).
struct JobTruth {
  Extrinsic extrinsic;
  std::string file;
  // The true camera time offset, when the file says (readTimeOffset): the truth's own loss is
  // taken with the points at that instant, when the result moved points in time at all.
  std::optional<double> time_offset_s;
};

struct CalibrationJobRequest {
  CameraModel camera;
  std::vector<CalibrationPair> pairs;  // the kept pairs, in time order
  // Issue 23: the frames the count rule did not keep, with people in both modalities
  // (DatasetBuilder::takeCandidates), paired by association after the first fit when
  // parameters.pairing says so. Empty: the count rule's pairs alone. The frames the skip rule
  // passed over (DatasetBuilder::takeSkippedFrames, outside_skip_rule) go among them in time
  // order (inOfferOrder), for the association's final round.
  std::vector<CalibrationPair> candidates;
  // The front end kept candidates (DatasetBuilder::keepAssociationCandidates): without them the
  // result says association was not applied, rather than that it found nothing.
  bool candidates_collected = false;
  // Where association may start instead of the first fit. Unset: the job reads
  // parameters.initial_extrinsic_file, if any (a front end may read it first to fail early).
  std::optional<InitialExtrinsic> initial;
  CoreParameters parameters;           // the fit's and the quality's settings, written to the file
  std::optional<JobReference> reference;
  std::optional<JobTruth> truth;
  std::string lidar_frame, camera_frame;  // empty: "lidar" / "camera"
  std::string source;        // result file `source:`: the bag's path, or "live"
  std::string report_title;  // the report's source line: "calibrate_bag drive.bag"
  std::string output_file;   // the result file; empty: not written
  std::string report_dir;    // the report's folder; empty: no report
  // A fit stopped by the callback still writes its best so far (calibrate_bag on Ctrl-C: the
  // work done is not lost); the node drops a stopped run (it was reset or is shutting down).
  bool write_stopped_result = false;
};

// What the job is doing, for the callback.
struct JobProgress {
  enum class Stage : std::uint8_t { kFit, kUncertainty, kWriting };
  Stage stage = Stage::kFit;
  Progress fit;        // kFit: the calibrator's own progress
  int resample = 0;    // kUncertainty: bootstrap resamples done of `resamples`
  int resamples = 0;
};
// Return false to stop: the fit returns its best so far, the bootstrap is skipped, and (unless
// write_stopped_result) nothing is written.
using JobCallback = std::function<bool(const JobProgress&)>;

struct CalibrationJobOutcome {
  std::optional<CalibrationResult> result;  // absent when the fit failed (`error` says why)
  std::optional<QualityAssessment> quality;  // after a fit that was not stopped
  std::string error;          // the fit failed on these pairs
  std::string quality_error;  // the assessment failed; the result stands
  ResultContext context;      // what the result file holds besides the result (~save rewrites it)
  bool result_file_written = false;  // written and read back
  std::string result_file_error;     // why not, when a file was asked for
  std::vector<std::string> report_files;
  std::string report_error;          // why the report is missing, when one was asked for
  std::size_t pairs = 0;             // pairs the job fitted
  // Issue 23: the pairs the result indexes (the count rule's and the association's, in time
  // order), how many each rule gave, and how the association went.
  std::vector<CalibrationPair> fitted_pairs;
  PairingSummary pairing;
};

// Runs the whole job. Never throws for bad pairs or unwritable files: the outcome says what
// failed (the front ends report it in their own terms).
CalibrationJobOutcome runCalibrationJob(const CalibrationJobRequest& request,
                                        const JobCallback& callback = {});

// An initial extrinsic from a result YAML (its extrinsic, and its time offset unless it applied
// none). Throws std::invalid_argument("initial_extrinsic_file: ...") naming what is wrong.
InitialExtrinsic readInitialExtrinsic(const std::string& path);

// Writes the result file and reads it back; "" when the file holds the result, else why not.
std::string saveResultFile(const std::string& path, const CalibrationResult& result,
                           const ResultContext& context);

}  // namespace thermal_lidar_calibration
