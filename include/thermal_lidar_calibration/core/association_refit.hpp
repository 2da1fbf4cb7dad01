#pragma once
// The default run's pairing (issue 23, beyond the paper): a first fit on the count rule's pairs
// exactly as the paper makes it, then every candidate frame (a frame the count rule did not keep
// but with people in both modalities) paired person by person at the current extrinsic
// (person_association.hpp), a refit on the enlarged set, and again, until the set stops
// changing. A pair made by association alone never decides the first fit: the association must
// not be able to drag a wrong extrinsic into a self-consistent one. An initial extrinsic (a
// result file the user gives) replaces the first fit only when the count rule's pairs agree
// with it; otherwise it is refused and the paper's first fit is run, and the note says so.
// pairing counts, or refine none (the paper's method), is the count rule's fit alone. Issue 24:
// candidates marked outside_skip_rule (frames the skip rule passed over) wait for a final round
// that pairs every frame once the rounds have converged. ROS-free.

#include "thermal_lidar_calibration/core/calibration_config.hpp"
#include "thermal_lidar_calibration/core/calibration_pair.hpp"
#include "thermal_lidar_calibration/core/calibrator.hpp"
#include "thermal_lidar_calibration/core/camera_model.hpp"
#include "thermal_lidar_calibration/core/person_association.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace thermal_lidar_calibration {

enum class PairingMode : std::uint8_t { kCounts, kAssociation };
const char* toString(PairingMode mode);  // "counts", "association"

struct PairingConfig {
  PairingMode mode = PairingMode::kAssociation;
  AssociationConfig association;
  // An initial extrinsic is used only when at least this share of the count rule's pairs lie
  // within threshold_sample_px of it (Eq. 1). At the truth 86 and 100 % of the count rule's pairs
  // do on two raw MS2-like drives (docs/validation/association.md); 5 deg and 30 cm off, none.
  double min_initial_agreement = 0.3;
  // Issue 24: after the rounds, one association with the skip rule off over every candidate and
  // skipped frame, and a refinement on that set (calibrateWithAssociation).
  bool final_round = true;
  static const ParameterRanges<PairingConfig>& ranges();  // checked by validate()
  void validate() const;  // throws std::invalid_argument naming the key and range
};

// Whether a run pairs by association: asked for, and not the paper's mode (refine none is the
// paper's method alone, the count rule only).
bool pairsByAssociation(const PairingConfig& pairing, const CalibrationConfig& config);

// What the gate settings mean for association pairs: H_max caps the people matched in a pair,
// and after any pair the next skip_frames candidate frames make none.
struct PairingLimits {
  int max_people = 3;
  int skip_frames = 3;
};

// What pairing a frame by association needs besides the extrinsic: the matcher's settings and
// the gate's limits (the calibration's rounds and the drift watch alike).
struct AssociationPairing {
  AssociationConfig config;
  PairingLimits limits;
};

struct InitialExtrinsic {
  Extrinsic extrinsic;
  std::optional<double> time_offset_s;  // the file's, when it applied one
  std::string origin;                   // for the note: the file's path
};

struct AssociatedCalibration {
  CalibrationResult result;
  // The pairs the result's per-pair fields index: the count rule's, then (merged in time order)
  // those made by association.
  std::vector<CalibrationPair> pairs;
  std::size_t counts_pairs = 0;
  std::size_t association_pairs = 0;
  int rounds = 0;           // association rounds run (0: none)
  bool converged = true;    // the set stopped changing within association_max_rounds
  bool initial_used = false;
  std::string note;         // one line when something differs from the plain path (refused start, ...)
  // The final round (PairingConfig::final_round): run, the pairs it made that the rounds did not
  // (outside_skip_rule; counted in association_pairs too), and its refinement's work.
  bool final_round = false;
  std::size_t final_round_pairs = 0;
  std::uint64_t final_round_evaluations = 0, final_round_points = 0;
};

// Throws std::invalid_argument as calibrate() does (no count-rule pairs, bad config).
AssociatedCalibration calibrateWithAssociation(const CameraModel& camera, std::vector<CalibrationPair> count_pairs,
                                               const std::vector<CalibrationPair>& candidates,
                                               const CalibrationConfig& config, const PairingConfig& pairing,
                                               const PairingLimits& limits,
                                               const std::optional<InitialExtrinsic>& initial = std::nullopt,
                                               const ProgressCallback& progress = {});

// One candidate frame paired at an extrinsic and time offset: nullopt when no cluster matched or
// more than H_max did (the skip rule is the caller's: it depends on the pairs around the frame).
std::optional<CalibrationPair> associateCandidate(const CameraModel& camera, const CalibrationPair& frame,
                                                 const Extrinsic& extrinsic, std::optional<double> time_offset_s,
                                                 const AssociationConfig& config, const PairingLimits& limits);

// The association pairs of `candidates` at an extrinsic and time offset, with the skip rule
// counted from the count rule's pairs (`count_indices`, their candidate_index, sorted) and from
// each other. With a time offset the points are moved to the image's instant (as the loss moves
// them); without one (timing not applied) they stay where they were captured. Exposed for tests
// and measurements.
std::vector<CalibrationPair> associatePairs(const CameraModel& camera, const std::vector<CalibrationPair>& candidates,
                                            const std::vector<std::uint64_t>& count_indices,
                                            const Extrinsic& extrinsic, std::optional<double> time_offset_s,
                                            const AssociationConfig& config, const PairingLimits& limits);

}  // namespace thermal_lidar_calibration
