#pragma once
// The YAML result file of INTERFACE.md (plus per-pair detail, parameters, seed, run time),
// and a reader for result / truth files (same keys).

#include "thermal_lidar_calibration/core/association_refit.hpp"
#include "thermal_lidar_calibration/core/quality_assessment.hpp"
#include "thermal_lidar_calibration/core/calibrator.hpp"
#include "thermal_lidar_calibration/app/parameters/core_parameters.hpp"

#include <optional>
#include <string>
#include <vector>

namespace YAML {
class Emitter;
}  // namespace YAML

namespace thermal_lidar_calibration {

// The result against a known truth (calibrate_bag --truth, synthetic bags).
struct TruthComparison {
  std::string truth_file;
  double rotation_error_rad = 0.0;
  double translation_error_m = 0.0;
  double truth_loss = 0.0;  // Eq. (3), nearest rule, on the pairs the result used
};

// How the pairs were made (issue 23): result YAML `pairs_by_rule: {counts: N, association: M}`
// and an `association:` block.
struct PairingSummary {
  PairingMode mode = PairingMode::kCounts;  // as applied (refine none: counts)
  std::size_t counts = 0;
  std::size_t association = 0;
  std::size_t candidates = 0;  // frames association could pair
  // Issue 24: the frames the skip rule passed over among them, whether the final round ran, and
  // the pairs it made that the rounds did not (within `association`).
  std::size_t skipped_frames = 0;
  bool final_round = false;
  std::size_t final_round_pairs = 0;
  int rounds = 0;
  bool converged = true;
  bool initial_used = false;
  std::string note;
};

struct ResultContext {
  std::string lidar_frame;
  std::string camera_frame;
  std::string source;                  // bag path or "live"
  std::vector<double> pair_stamps_s;   // one per collected pair, same order as the result
  std::vector<PairRule> pair_rules;    // the same pairs' rules (issue 23); empty: not written
  CoreParameters parameters;
  std::optional<TruthComparison> truth;  // written as a `truth:` block when set
  std::optional<QualityAssessment> quality;  // uncertainty, coverage, verdict, reference keys
  std::optional<PairingSummary> pairing;     // pairs_by_rule and association: when set
};

// Throws std::runtime_error if the file cannot be written (says the path and the reason).
void writeResultFile(const std::string& path, const CalibrationResult& result,
                     const ResultContext& context);
// Reads rotation_vector (or rotation_matrix) and translation. Throws std::invalid_argument.
Extrinsic readExtrinsicFile(const std::string& path);
// The file's camera time offset (issue 21), if it has one: `time_offset_s`, or with
// `point_times` false `time_offset_at_scan_stamp_s` when present (a synthetic truth file: the
// offset a fit that reads no per-point times should find). Throws std::invalid_argument on a
// non-number.
std::optional<double> readTimeOffset(const std::string& path, bool point_times);
// The camera time offset a result file's extrinsic goes with: its time_offset_s, unless its
// time_offset_mode is none (then, and without the key, nullopt).
std::optional<double> readAppliedTimeOffset(const std::string& path);
// Reads `path` back after a write and throws std::runtime_error naming it unless it holds
// `expected` (a full disk can take the rename and lose the data: a write not checked is not one).
void checkExtrinsicFile(const std::string& path, const Extrinsic& expected);

// Building blocks of the result file, shared with make_synthetic_bag's truth file. Both write
// into a map the caller has opened; numbers use the caller's emitter precision.
// `key: [v[0], ..., v[n-1]]` as a flow sequence.
void emitVector(YAML::Emitter& out, const std::string& key, const double* v, int n);
// rotation_vector, translation, rotation_matrix (row-major) and quaternion_xyzw, in that order.
void emitExtrinsic(YAML::Emitter& out, const Extrinsic& e);

}  // namespace thermal_lidar_calibration
