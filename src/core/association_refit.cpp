#include "thermal_lidar_calibration/core/association_refit.hpp"

#include "thermal_lidar_calibration/core/distance_map.hpp"
#include "thermal_lidar_calibration/core/inlier_selection.hpp"
#include "thermal_lidar_calibration/core/loss.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>
#include <memory>
#include <stdexcept>
#include <utility>

namespace thermal_lidar_calibration {
namespace {

// Which clusters of which candidate frame an association paired: the set the rounds compare.
using Signature = std::vector<std::pair<std::uint64_t, std::vector<std::int32_t>>>;

Signature signatureOf(const std::vector<CalibrationPair>& pairs) {
  Signature s;
  for (const CalibrationPair& p : pairs) {
    std::vector<std::int32_t> labels = p.labels;
    std::sort(labels.begin(), labels.end());
    labels.erase(std::unique(labels.begin(), labels.end()), labels.end());
    s.emplace_back(p.candidate_index, std::move(labels));
  }
  return s;
}

// Each frame's distance map, built once for all the fits and checks that read its pair: every
// round pairs the same candidate frames again, and each refit, the quality and the truth's loss
// read them all. Frames are told apart by candidate_index when the candidates' are distinct
// (a builder's always are); otherwise each pair gets its own map.
class DistanceMaps {
 public:
  explicit DistanceMaps(const std::vector<CalibrationPair>& candidates) {
    std::vector<std::uint64_t> indices;
    for (const CalibrationPair& c : candidates) indices.push_back(c.candidate_index);
    std::sort(indices.begin(), indices.end());
    by_frame_ = std::adjacent_find(indices.begin(), indices.end()) == indices.end();
  }
  // The count rule's pairs: each its own map (their copies in every round share it).
  static void attachOwn(std::vector<CalibrationPair>& pairs) {
    for (CalibrationPair& p : pairs) {
      if (!p.distance_map) p.distance_map = sharedDistanceMap(p.mask);
    }
  }
  // Pairs made by association from the candidates.
  void attach(std::vector<CalibrationPair>& associated) {
    for (CalibrationPair& p : associated) {
      if (p.distance_map) continue;
      if (!by_frame_) {
        p.distance_map = sharedDistanceMap(p.mask);
        continue;
      }
      std::shared_ptr<const DistanceMap>& map = maps_[p.candidate_index];
      if (!map) map = sharedDistanceMap(p.mask);
      p.distance_map = map;
    }
  }

 private:
  bool by_frame_ = false;
  std::map<std::uint64_t, std::shared_ptr<const DistanceMap>> maps_;
};

// The count rule's pairs and the association's, in candidate (time) order.
std::vector<CalibrationPair> merged(const std::vector<CalibrationPair>& counts,
                                    const std::vector<CalibrationPair>& associated) {
  std::vector<CalibrationPair> out;
  out.reserve(counts.size() + associated.size());
  std::merge(counts.begin(), counts.end(), associated.begin(), associated.end(), std::back_inserter(out),
             [](const CalibrationPair& a, const CalibrationPair& b) { return a.candidate_index < b.candidate_index; });
  return out;
}

// The time offset the result's loss applied (none: points stay where they were captured).
std::optional<double> appliedOffset(const CalibrationResult& r) {
  if (r.time_offset_mode == TimeOffsetMode::kNone) return std::nullopt;
  return r.time_offset_s;
}

// The share of the count rule's pairs within threshold_sample_px of `initial` (Eq. 1).
double agreement(const CameraModel& camera, const std::vector<CalibrationPair>& pairs,
                 const CalibrationConfig& config, const InitialExtrinsic& initial) {
  std::optional<double> offset;
  if (config.time_offset.mode != TimeOffsetMode::kNone) {
    offset = initial.time_offset_s.value_or(config.time_offset.offset_s);
  }
  const LossEvaluator nearest(camera, pairs, LossConfig{config.behind_camera_penalty_c1, PixelRule::kNearest, offset});
  return shareWithinThreshold(nearest, initial.extrinsic, config.outlier.threshold_px);
}

// The first fit: from the initial extrinsic when the count rule's pairs agree with it, else the
// paper's (Algorithm 1 or 2 and the refinement, exactly as without association).
CalibrationResult firstFit(const CameraModel& camera, const std::vector<CalibrationPair>& counts,
                           const CalibrationConfig& config, const PairingConfig& pairing,
                           const std::optional<InitialExtrinsic>& initial, const ProgressCallback& progress,
                           AssociatedCalibration& out) {
  if (!initial) return calibrate(camera, counts, config, progress);
  if (counts.empty()) throw std::invalid_argument("calibration: no pairs were collected");
  const double share = agreement(camera, counts, config, *initial);
  char note[400];
  if (share >= pairing.min_initial_agreement) {
    out.initial_used = true;
    std::snprintf(note, sizeof(note),
                  "started from the initial extrinsic %s: %.0f %% of the count rule's %zu pairs agree with it",
                  initial->origin.c_str(), 100.0 * share, counts.size());
    out.note = note;
    const double offset = initial->time_offset_s.value_or(config.time_offset.offset_s);
    return refineFrom(camera, counts, config, initial->extrinsic, offset, progress);
  }
  std::snprintf(note, sizeof(note),
                "initial extrinsic %s refused: only %.0f %% of the count rule's %zu pairs lie within "
                "threshold_sample_px of it (initial_extrinsic_min_agreement %.0f %%); started from the paper's fit",
                initial->origin.c_str(), 100.0 * share, counts.size(), 100.0 * pairing.min_initial_agreement);
  out.note = note;
  return calibrate(camera, counts, config, progress);
}

// The refit's result, with what the first fit found that the refit does not redo (the evolution,
// its history, the work counted).
void carryOver(const CalibrationResult& first, CalibrationResult& refit) {
  refit.evolution_extrinsic = first.evolution_extrinsic;
  refit.evolution_full_length = first.evolution_full_length;
  refit.evolution_loss = first.evolution_loss;
  refit.outlier_fits_accepted = first.outlier_fits_accepted;
  std::vector<ConvergenceStep> history = first.history;
  history.insert(history.end(), refit.history.begin(), refit.history.end());
  refit.history = std::move(history);
}

// Issue 21: a refit from a fit that estimated the time offset searches near that estimate only
// (OffsetSearchReach::kNearStart) and keeps that fit's profile over the whole range.
OffsetSearchReach reachAfter(const CalibrationResult& before) {
  return before.time_offset_mode == TimeOffsetMode::kEstimate ? OffsetSearchReach::kNearStart
                                                              : OffsetSearchReach::kWholeRange;
}

void carryProfile(const CalibrationResult& before, CalibrationResult& refit) {
  if (!refit.time_offset_profile_s.empty()) return;
  refit.time_offset_profile_s = before.time_offset_profile_s;
  refit.time_offset_profile_loss = before.time_offset_profile_loss;
  refit.time_offset_profile_pairs = before.time_offset_profile_pairs;
}

// The ring alias check of every fit so far counts in `refit`'s report (a turn kept in an earlier
// fit moved the start of this one): the starts add up, the turn and the spacing are the latest
// fit's that has one (the final round refines without the check and keeps the rounds').
void addRingAliasReport(const CalibrationResult& before, CalibrationResult& refit) {
  refit.ring_alias_tried += before.ring_alias_tried;
  if (refit.ring_alias_turn == 0) refit.ring_alias_turn = before.ring_alias_turn;
  if (!(refit.ring_spacing_rad > 0.0)) refit.ring_spacing_rad = before.ring_spacing_rad;
}

// Issue 24: one more association at the converged extrinsic with the skip rule off, over every
// candidate and skipped frame, and a refinement on that set from where the rounds ended. Between
// two kept frames the people move a few centimetres: their rings meet them at other heights,
// which is what the vertical fit lacks on sparse pairs (a ring every 1.33 deg). The rounds'
// evolution-free refits stay on the spaced pairs, so a frame of this round never decides which
// basin the fit is in. A pair the rounds did not make is marked outside_skip_rule.
void finalRound(const CameraModel& camera, const std::vector<CalibrationPair>& counts,
                const std::vector<CalibrationPair>& candidates, const std::vector<std::uint64_t>& count_indices,
                const CalibrationConfig& config, const PairingConfig& pairing, const PairingLimits& limits,
                const CalibrationResult& first, const ProgressCallback& progress, DistanceMaps& maps,
                AssociatedCalibration& out) {
  std::vector<std::uint64_t> spaced;  // the frames the rounds paired
  for (const CalibrationPair& p : out.pairs) {
    if (p.rule == PairRule::kAssociation) spaced.push_back(p.candidate_index);
  }
  std::sort(spaced.begin(), spaced.end());
  PairingLimits every_frame = limits;
  every_frame.skip_frames = 0;
  std::vector<CalibrationPair> associated =
      associatePairs(camera, candidates, count_indices, out.result.extrinsic, appliedOffset(out.result),
                     pairing.association, every_frame);
  if (associated.size() <= out.association_pairs) return;  // nothing the rounds did not have
  maps.attach(associated);
  for (CalibrationPair& p : associated) {
    p.outside_skip_rule = !std::binary_search(spaced.begin(), spaced.end(), p.candidate_index);
  }
  std::vector<CalibrationPair> enlarged = merged(counts, associated);
  // The ring alias check ran on the rounds' fits; from their end there is no ring to turn.
  CalibrationConfig final_config = config;
  final_config.refine.ring_alias_turns = 0;
  CalibrationResult refit = refineFrom(camera, enlarged, final_config, out.result.extrinsic,
                                       out.result.time_offset_s, progress, reachAfter(out.result));
  out.final_round_evaluations = refit.evaluations;
  out.final_round_points = refit.points_projected;
  carryOver(first, refit);
  addRingAliasReport(out.result, refit);
  carryProfile(out.result, refit);
  out.result = std::move(refit);
  out.pairs = std::move(enlarged);
  out.association_pairs = associated.size();
  out.final_round_pairs = static_cast<std::size_t>(
      std::count_if(out.pairs.begin(), out.pairs.end(), [](const CalibrationPair& p) { return p.outside_skip_rule; }));
  out.final_round = true;
}

}  // namespace

const char* toString(PairingMode mode) {
  return mode == PairingMode::kCounts ? "counts" : "association";
}

bool pairsByAssociation(const PairingConfig& pairing, const CalibrationConfig& config) {
  return pairing.mode == PairingMode::kAssociation && config.refine.mode == RefineMode::kLocal;
}

const ParameterRanges<PairingConfig>& PairingConfig::ranges() {
  static const auto ranges = ParameterRanges<PairingConfig>()
      .add("initial_extrinsic_min_agreement", &PairingConfig::min_initial_agreement, closedRange(0, 1));
  return ranges;
}

void PairingConfig::validate() const {
  association.validate();
  ranges().check(*this);
}

std::optional<CalibrationPair> associateCandidate(const CameraModel& camera, const CalibrationPair& frame,
                                                 const Extrinsic& extrinsic, std::optional<double> time_offset_s,
                                                 const AssociationConfig& config, const PairingLimits& limits) {
  const FrameAssociation a = associateFrame(camera, frame, extrinsic, time_offset_s, config);
  if (a.matches.empty() || static_cast<int>(a.matches.size()) > limits.max_people) return std::nullopt;
  return associatedPair(frame, a);
}

std::vector<CalibrationPair> associatePairs(const CameraModel& camera, const std::vector<CalibrationPair>& candidates,
                                            const std::vector<std::uint64_t>& count_indices,
                                            const Extrinsic& extrinsic, std::optional<double> time_offset_s,
                                            const AssociationConfig& config, const PairingLimits& limits) {
  std::vector<CalibrationPair> out;
  std::size_t next_count = 0;
  bool have_last = false;
  std::uint64_t last = 0;  // candidate index of the latest pair, either rule
  for (const CalibrationPair& frame : candidates) {
    while (next_count < count_indices.size() && count_indices[next_count] < frame.candidate_index) {
      last = have_last ? std::max(last, count_indices[next_count]) : count_indices[next_count];
      have_last = true;
      ++next_count;
    }
    if (have_last && frame.candidate_index <= last + static_cast<std::uint64_t>(limits.skip_frames)) continue;
    std::optional<CalibrationPair> pair = associateCandidate(camera, frame, extrinsic, time_offset_s, config, limits);
    if (!pair) continue;
    out.push_back(std::move(*pair));
    last = frame.candidate_index;
    have_last = true;
  }
  return out;
}

AssociatedCalibration calibrateWithAssociation(const CameraModel& camera, std::vector<CalibrationPair> count_pairs,
                                               const std::vector<CalibrationPair>& candidates,
                                               const CalibrationConfig& config, const PairingConfig& pairing,
                                               const PairingLimits& limits,
                                               const std::optional<InitialExtrinsic>& initial,
                                               const ProgressCallback& progress) {
  const auto started = std::chrono::steady_clock::now();
  pairing.validate();
  AssociatedCalibration out;
  out.counts_pairs = count_pairs.size();
  const bool associate = pairsByAssociation(pairing, config);
  // The paper's mode takes no start either: it is the paper's method alone.
  const std::optional<InitialExtrinsic> start = associate ? initial : std::nullopt;
  if (initial && !start) out.note = "initial extrinsic not used: pairing counts / refine none fit as the paper does";

  DistanceMaps maps(candidates);
  DistanceMaps::attachOwn(count_pairs);
  const CalibrationResult first = firstFit(camera, count_pairs, config, pairing, start, progress, out);
  out.result = first;
  out.pairs = std::move(count_pairs);
  if (!associate || candidates.empty() || first.stopped) return out;

  std::vector<std::uint64_t> count_indices;
  for (const CalibrationPair& p : out.pairs) count_indices.push_back(p.candidate_index);
  const std::vector<CalibrationPair> counts = out.pairs;
  // The rounds pair the frames the skip rule let through; the final round all of them.
  std::vector<CalibrationPair> spaced;
  bool skipped_frames = false;
  for (const CalibrationPair& c : candidates) {
    if (!c.outside_skip_rule) spaced.push_back(c);
    skipped_frames = skipped_frames || c.outside_skip_rule;
  }
  std::uint64_t evaluations = first.evaluations, points = first.points_projected;
  Signature previous;
  out.converged = false;
  for (int round = 1; round <= pairing.association.max_rounds; ++round) {
    std::vector<CalibrationPair> associated =
        associatePairs(camera, spaced, count_indices, out.result.extrinsic, appliedOffset(out.result),
                       pairing.association, limits);
    maps.attach(associated);
    out.rounds = round;
    Signature now = signatureOf(associated);
    if (now == previous) {  // the last refit was on this very set
      out.converged = true;
      break;
    }
    if (associated.empty()) {  // nothing pairs at this extrinsic: the count rule's fit stands
      out.result = first;
      out.pairs = counts;
      out.association_pairs = 0;
      out.converged = true;
      break;
    }
    std::vector<CalibrationPair> enlarged = merged(counts, associated);
    CalibrationResult refit = refineFrom(camera, enlarged, config, out.result.extrinsic,
                                         out.result.time_offset_s, progress, reachAfter(out.result));
    evaluations += refit.evaluations;
    points += refit.points_projected;
    carryOver(first, refit);
    addRingAliasReport(out.result, refit);
    carryProfile(out.result, refit);
    out.result = std::move(refit);
    out.pairs = std::move(enlarged);
    out.association_pairs = associated.size();
    previous = std::move(now);
    if (out.result.stopped) break;
  }
  if (pairing.final_round && (skipped_frames || limits.skip_frames > 0) && !out.result.stopped) {
    finalRound(camera, counts, candidates, count_indices, config, pairing, limits, first, progress, maps, out);
    evaluations += out.final_round_evaluations;
    points += out.final_round_points;
  }
  out.result.evaluations = evaluations;
  out.result.points_projected = points;
  out.result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  if (!out.converged && !out.result.stopped) {
    char note[200];
    std::snprintf(note, sizeof(note), "association still changed the pairs after association_max_rounds %d",
                  pairing.association.max_rounds);
    out.note += (out.note.empty() ? "" : "; ") + std::string(note);
  }
  return out;
}

}  // namespace thermal_lidar_calibration
