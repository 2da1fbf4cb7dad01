#include "thermal_lidar_calibration/core/uncertainty.hpp"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include "thermal_lidar_calibration/core/local_refinement.hpp"
#include "thermal_lidar_calibration/core/pose_difference.hpp"
#include "thermal_lidar_calibration/core/random.hpp"
#include "thermal_lidar_calibration/core/timed_refinement.hpp"
#include "thermal_lidar_calibration/core/vertical_centring.hpp"
#include "threads.hpp"

namespace thermal_lidar_calibration {
namespace {

// Resample b's own seed (splitmix64): independent streams, whatever thread runs them.
std::uint64_t resampleSeed(std::uint64_t seed, std::uint64_t b) {
  std::uint64_t z = seed + 0x9E3779B97F4A7C15ULL * (b + 1);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

// n pairs drawn with replacement, in blocks of `block` consecutive pairs (moving-block
// bootstrap: blocks start anywhere in [0, n - block]).
std::vector<std::size_t> drawResample(const std::vector<std::size_t>& pairs, int block, Rng& rng) {
  const std::size_t n = pairs.size();
  const std::size_t len = std::min<std::size_t>(static_cast<std::size_t>(block), n);
  std::vector<std::size_t> out;
  out.reserve(n + len);
  while (out.size() < n) {
    const std::size_t start = rng.index(n - len + 1);
    for (std::size_t k = 0; k < len && out.size() < n; ++k) out.push_back(pairs[start + k]);
  }
  return out;
}

// Linear interpolation between order statistics (the common "type 7" definition).
double quantile(std::vector<double> values, double q) {
  std::sort(values.begin(), values.end());
  const double pos = q * static_cast<double>(values.size() - 1);
  const std::size_t lo = static_cast<std::size_t>(std::floor(pos));
  const std::size_t hi = std::min(lo + 1, values.size() - 1);
  return values[lo] + (pos - static_cast<double>(lo)) * (values[hi] - values[lo]);
}

void summarise(Uncertainty& u) {
  const double tail = (1.0 - u.confidence) / 2.0;
  for (int k = 0; k < 6; ++k) {
    std::vector<double> axis;
    axis.reserve(u.deviations.size());
    for (const Vector6d& d : u.deviations) axis.push_back(d[k]);
    u.lower[k] = quantile(axis, tail);
    u.upper[k] = quantile(axis, 1.0 - tail);
    u.mean[k] = std::accumulate(axis.begin(), axis.end(), 0.0) / static_cast<double>(axis.size());
    double sum_sq = 0.0;
    for (double a : axis) sum_sq += (a - u.mean[k]) * (a - u.mean[k]);
    u.std_dev[k] = std::sqrt(sum_sq / static_cast<double>(axis.size() - 1));
    // Symmetric about the estimate and wide enough to hold the whole percentile interval: the
    // interval a user reads as "estimate +- half-width".
    const double half = std::max(std::abs(u.lower[k]), std::abs(u.upper[k]));
    (k < 3 ? u.rotation_deg[k] : u.translation_cm[k - 3]) = half;
  }
  if (!u.timed) return;
  const std::vector<double>& d = u.time_offset_deviations_ms;
  u.time_offset_lower_ms = quantile(d, tail);
  u.time_offset_upper_ms = quantile(d, 1.0 - tail);
  u.time_offset_ms = std::max(std::abs(u.time_offset_lower_ms), std::abs(u.time_offset_upper_ms));
  const double mean = std::accumulate(d.begin(), d.end(), 0.0) / static_cast<double>(d.size());
  double sdd = 0.0;
  for (double v : d) sdd += (v - mean) * (v - mean);
  u.time_offset_std_ms = std::sqrt(sdd / static_cast<double>(d.size() - 1));
  for (int axis = 0; axis < 3; ++axis) {
    double sxy = 0.0;
    for (std::size_t b = 0; b < d.size(); ++b) {
      sxy += (d[b] - mean) * (u.deviations[b][3 + axis] - u.mean[3 + axis]);
    }
    const double denominator = std::sqrt(sdd) * u.std_dev[3 + axis] * std::sqrt(static_cast<double>(d.size() - 1));
    u.time_translation_correlation[axis] = denominator > 0.0 ? sxy / denominator : 0.0;
  }
}

// Throws std::invalid_argument on a bad config, fewer than 3 pairs, an index past the
// evaluator's pairs, or a time offset to refine with an evaluator that has none.
void requireUsableInput(const LossEvaluator& loss, const std::vector<std::size_t>& pairs,
                        const UncertaintyConfig& config, const std::optional<TimeOffsetConfig>& timing) {
  config.validate();
  if (pairs.size() < 3) {
    throw std::invalid_argument("uncertainty: needs at least 3 pairs, got " +
                                std::to_string(pairs.size()));
  }
  for (std::size_t i : pairs) {
    if (i >= loss.pairCount()) throw std::invalid_argument("uncertainty: pair index out of range");
  }
  if (timing && !loss.config().time_offset_s) {
    throw std::invalid_argument("uncertainty: a time offset to refine needs an evaluator with one");
  }
}

// The centring's outcome with its fitting pairs (sorted indices into the whole evaluator) given
// as positions in `pairs`, the indices of an evaluator over those pairs alone (ofPairs).
VerticalCentringOutcome withLocalFitting(const VerticalCentringOutcome& centring, const std::vector<std::size_t>& pairs) {
  VerticalCentringOutcome out = centring;
  out.fitting.clear();
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    if (std::binary_search(centring.fitting.begin(), centring.fitting.end(), pairs[k])) out.fitting.push_back(k);
  }
  return out;
}

// Each resample's refinement: the calibration's local refinement with the bootstrap's steps.
RefineConfig resampleRefineConfig(const UncertaintyConfig& config) {
  RefineConfig refine;
  refine.initial_step_rot_rad = config.initial_step_rot_rad;
  refine.initial_step_trans_m = config.initial_step_trans_m;
  refine.min_step_rot_rad = config.min_step_rot_rad;
  refine.min_step_trans_m = config.min_step_trans_m;
  refine.max_evaluations = config.max_evaluations;
  return refine;
}

}  // namespace

UncertaintyConfig UncertaintyConfig::quick() {
  UncertaintyConfig c;
  c.resamples = 30;
  c.min_step_rot_rad = 1e-4;
  c.min_step_trans_m = 1e-4;
  c.max_evaluations = 1500;
  return c;
}

const ParameterRanges<UncertaintyConfig>& UncertaintyConfig::ranges() {
  static const auto ranges = ParameterRanges<UncertaintyConfig>()
      .add("uncertainty_resamples", &UncertaintyConfig::resamples, IntRange{2, 100000})
      .add("uncertainty_block_pairs", &UncertaintyConfig::block_pairs, IntRange{1, 100000})
      .add("uncertainty_confidence", &UncertaintyConfig::confidence, aboveRange(0.0, 0.9999))
      .add("uncertainty_num_threads", &UncertaintyConfig::num_threads, IntRange{0, 1024})
      .add("uncertainty_initial_step_rot_rad", &UncertaintyConfig::initial_step_rot_rad, aboveRange(0.0, 1.0))
      .add("uncertainty_initial_step_trans_m", &UncertaintyConfig::initial_step_trans_m, aboveRange(0.0, 10.0))
      .add("uncertainty_max_evaluations", &UncertaintyConfig::max_evaluations, IntRange{1, 100000000})
      .add("uncertainty_initial_step_time_s", &UncertaintyConfig::initial_step_time_s, aboveRange(0.0, 1.0))
      .add("uncertainty_min_step_time_s", &UncertaintyConfig::min_step_time_s, aboveRange(0.0, 1.0));
  return ranges;
}

void UncertaintyConfig::validate() const {
  ranges().check(*this);
  requireRange("uncertainty_min_step_rot_rad", min_step_rot_rad, 0.0, initial_step_rot_rad, true);
  requireRange("uncertainty_min_step_trans_m", min_step_trans_m, 0.0, initial_step_trans_m, true);
}

std::vector<std::size_t> resamplePairs(const std::vector<std::size_t>& pairs, int block_pairs,
                                       std::uint64_t seed, int index) {
  if (pairs.empty() || block_pairs < 1) {
    throw std::invalid_argument("resamplePairs: needs pairs and block_pairs >= 1");
  }
  Rng rng(resampleSeed(seed, static_cast<std::uint64_t>(index)));
  return drawResample(pairs, block_pairs, rng);
}

std::string Uncertainty::method() const {
  std::ostringstream s;
  s << "bootstrap over pairs";
  if (block_pairs > 1) s << " in blocks of " << block_pairs;
  s << ", " << resamples << " resamples, local refinement from the estimate";
  if (timed) s << " with the time offset";
  if (ring_ends) s << " reading the rings' ends";
  if (centred) s << ", then the vertical centring";
  return s.str();
}

Uncertainty estimateUncertainty(const LossEvaluator& loss, const Extrinsic& estimate,
                                const std::vector<std::size_t>& pairs,
                                const UncertaintyConfig& config,
                                const UncertaintyCallback& callback,
                                const std::optional<TimeOffsetConfig>& timing,
                                const VerticalCentringOutcome* centring) {
  const auto started = std::chrono::steady_clock::now();
  requireUsableInput(loss, pairs, config, timing);
  // The resamples are read with distances from the person pixels' centres (outline_px 0), not
  // from their outline as the estimate was: read from the outline, a pose that fits every pair
  // to within half a pixel costs nothing, a resample refined from there has no slope to follow
  // and would end where it started, an interval of zero. The centres' rule has its minimum a
  // little apart (the lean the outline takes out), so each resample's deviation is taken from
  // that rule's fit on all the pairs, not from the estimate.
  //
  // The resamples read only the pairs they draw from: an evaluator over those alone (its pair k is
  // pairs[k]), so an offset a timed resample visits moves these points, not those of every pair
  // the fit had (a fourth of them on a drive with the final round). Each pair reads the same, so
  // the fits are those over the original indices.
  const LossEvaluator bilinear = loss.ofPairs(pairs).withPixelRule(PixelRule::kBilinear).withOutline(0.0);
  std::vector<std::size_t> local(pairs.size());
  std::iota(local.begin(), local.end(), std::size_t{0});
  std::optional<VerticalCentringOutcome> local_centring;
  if (centring) local_centring = withLocalFitting(*centring, pairs);
  const RefineConfig refine = resampleRefineConfig(config);
  // One thread per resample: a resample's refinement evaluates 12 probes at a time, too few to
  // share well, while the resamples are independent.
  const LocalRefinement refinement(bilinear, refine, 1);
  std::optional<TimedRefinement> timed;
  double offset_s = 0.0;
  if (timing) {
    TimeOffsetConfig steps = *timing;
    steps.initial_step_s = config.initial_step_time_s;
    steps.min_step_s = std::min(config.min_step_time_s, steps.initial_step_s);
    timed.emplace(bilinear, refine, steps, 1);
    offset_s = *loss.config().time_offset_s;
  }

  struct Fit {
    Extrinsic pose;
    double offset_s = 0.0;
    std::uint64_t evaluations = 0;
  };
  // The fit a resample gets: the refinement from the estimate, then the centring as calibrate()
  // did it, with the points where the refinement left the offset.
  const auto fit = [&](const std::vector<std::size_t>& set) {
    Fit f;
    f.offset_s = offset_s;
    if (timed) {
      const TimedRefineOutcome out = timed->run(estimate, offset_s, set);
      f.pose = out.best;
      f.offset_s = out.time_offset_s;
      f.evaluations = out.evaluations;
    } else {
      const RefineOutcome out = refinement.run(estimate, set);
      f.pose = out.best;
      f.evaluations = out.evaluations;
    }
    if (local_centring) {
      const VerticalCentringOutcome centred =
          timed ? centreResample(bilinear.withTimeOffset(f.offset_s), f.pose, set, *local_centring, 1)
                : centreResample(bilinear, f.pose, set, *local_centring, 1);
      f.pose = centred.extrinsic;
      f.evaluations += centred.evaluations;
    }
    return f;
  };
  const Fit reference = fit(local);

  const int total = config.resamples;
  std::vector<Vector6d> deviations(static_cast<std::size_t>(total));
  std::vector<double> offset_deviations(static_cast<std::size_t>(total), 0.0);
  std::vector<char> done(static_cast<std::size_t>(total), 0);
  std::vector<std::uint64_t> evaluations(static_cast<std::size_t>(total), 0);
  std::atomic<bool> stop{false};
  std::atomic<int> finished{0};
  const int team = std::max(1, std::min(resolveThreads(config.num_threads), total));
#pragma omp parallel for schedule(dynamic, 1) num_threads(team)
  for (int b = 0; b < total; ++b) {
    if (stop.load()) continue;
    const std::size_t k = static_cast<std::size_t>(b);
    const std::vector<std::size_t> resample =
        resamplePairs(local, config.block_pairs, config.seed, b);
    const Fit f = fit(resample);
    offset_deviations[k] = 1000.0 * (f.offset_s - reference.offset_s);
    evaluations[k] = f.evaluations;
    deviations[k] = asVector(poseDifference(f.pose, reference.pose));
    done[k] = 1;
    const int n = ++finished;
    if (callback) {
#pragma omp critical(tlc_uncertainty_callback)
      if (!stop.load() && !callback(n, total)) stop = true;
    }
  }

  Uncertainty u;
  u.block_pairs = config.block_pairs;
  u.confidence = config.confidence;
  u.pairs = pairs.size();
  u.stopped = stop.load();
  u.timed = timing.has_value();
  u.ring_ends = loss.config().ring_end_weight > 0.0 && loss.ringEndCount() > 0;
  u.centred = centring != nullptr && centring->applied;
  u.evaluations = reference.evaluations;
  for (int b = 0; b < total; ++b) {
    if (!done[static_cast<std::size_t>(b)]) continue;
    u.deviations.push_back(deviations[static_cast<std::size_t>(b)]);
    if (u.timed) u.time_offset_deviations_ms.push_back(offset_deviations[static_cast<std::size_t>(b)]);
    u.evaluations += evaluations[static_cast<std::size_t>(b)];
  }
  u.resamples = static_cast<int>(u.deviations.size());
  if (u.resamples >= 2) summarise(u);
  u.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return u;
}

Uncertainty estimateUncertainty(const CameraModel& camera,
                                const std::vector<CalibrationPair>& pairs,
                                const Extrinsic& estimate, const UncertaintyConfig& config,
                                double behind_camera_penalty_c1) {
  const LossEvaluator loss(camera, pairs,
                           LossConfig{behind_camera_penalty_c1, PixelRule::kBilinear});
  std::vector<std::size_t> all(pairs.size());
  std::iota(all.begin(), all.end(), std::size_t{0});
  return estimateUncertainty(loss, estimate, all, config);
}

}  // namespace thermal_lidar_calibration
