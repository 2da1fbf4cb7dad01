// Speed of the calibration (Google Benchmark; not a test):
//   BM_LossThroughput  projected points per second on ONE core (items_per_second), for the
//                      nearest (paper) and bilinear (refinement) rules, with and without lens
//                      distortion;
//   BM_DefaultRun      the whole default calibration (Algorithm 2 at Table 1 + refinement) on
//                      60 pairs of ~100 points, 2 threads;
//   BM_QualityAfterRun the quality assessment after that run (100-resample bootstrap, coverage,
//                      verdict): issue 8 allows it at most the default run's own time.
// Run: scripts/benchmark.sh (builds Release, then runs this binary).
#include "thermal_lidar_calibration/core/calibrator.hpp"
#include "thermal_lidar_calibration/core/loss.hpp"
#include "thermal_lidar_calibration/core/quality_assessment.hpp"

#include "../test/support/synthetic_pairs.hpp"

#include <benchmark/benchmark.h>

using namespace thermal_lidar_calibration;

namespace {

const std::vector<CalibrationPair>& benchPairs(bool distorted) {
  static const auto make = [](bool d) {
    test_support::SyntheticPairsOptions o;
    o.pairs = 60;
    o.max_people = 1;
    o.points_per_person = 100;
    o.seed = 2024;
    return test_support::makeSyntheticPairs(test_support::fieldsafeCamera(d),
                                            test_support::fieldsafeTruth(), o);
  };
  static const std::vector<CalibrationPair> with = make(true), without = make(false);
  return distorted ? with : without;
}

std::vector<Extrinsic> candidatesNearTruth(int n) {
  Rng rng(5);
  std::vector<Extrinsic> out;
  const Extrinsic truth = test_support::fieldsafeTruth();
  for (int i = 0; i < n; ++i) {
    Extrinsic e = truth;
    for (int k = 0; k < 3; ++k) e.rotation_vector[k] += rng.uniform(-0.05, 0.05);
    for (int k = 0; k < 3; ++k) e.translation[k] += rng.uniform(-0.1, 0.1);
    out.push_back(e);
  }
  return out;
}

void BM_LossThroughput(benchmark::State& state) {
  const bool distorted = state.range(0) != 0;
  const PixelRule rule = state.range(1) != 0 ? PixelRule::kBilinear : PixelRule::kNearest;
  const auto& pairs = benchPairs(distorted);
  const LossEvaluator loss(test_support::fieldsafeCamera(distorted), pairs, LossConfig{5.0, rule});
  const auto candidates = candidatesNearTruth(500);
  std::size_t points = 0;
  for (const auto& p : pairs) points += p.points.size();
  std::vector<double> out;
  for (auto _ : state) {
    loss.lossBatch(candidates, {}, out, 1);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * candidates.size() * points);
  state.SetLabel(std::string(distorted ? "plumb_bob" : "pinhole") + ", " +
                 (rule == PixelRule::kNearest ? "nearest" : "bilinear") + ", " +
                 std::to_string(points) + " points");
}
BENCHMARK(BM_LossThroughput)
    ->ArgsProduct({{0, 1}, {0, 1}})
    ->ArgNames({"distorted", "bilinear"})
    ->Unit(benchmark::kMillisecond);

void BM_DefaultRun(benchmark::State& state) {
  const auto& pairs = benchPairs(true);
  CalibrationConfig config;  // Algorithm 2, Table 1, local refinement
  config.num_threads = static_cast<int>(state.range(0));
  double rot = 0, trans = 0, loss = 0, truth_loss = 0;
  for (auto _ : state) {
    const CalibrationResult r = calibrate(test_support::fieldsafeCamera(true), pairs, config);
    rot = rotationErrorRad(r.extrinsic, test_support::fieldsafeTruth()) * 180.0 / M_PI;
    trans = translationErrorM(r.extrinsic, test_support::fieldsafeTruth()) * 100.0;
    loss = r.loss_bilinear;
    state.PauseTiming();
    std::vector<std::size_t> used;
    for (std::size_t i = 0; i < r.inliers.size(); ++i) {
      if (r.inliers[i]) used.push_back(i);
    }
    const LossEvaluator bilinear(test_support::fieldsafeCamera(true), pairs,
                                 LossConfig{5.0, PixelRule::kBilinear});
    truth_loss = bilinear.loss(test_support::fieldsafeTruth(), used);
    state.ResumeTiming();
  }
  // Errors against the truth, and the bilinear loss (the refinement's) of the result and of the
  // truth on the same pairs: the truth's is the floor these toy pairs can show.
  state.counters["rot_err_deg"] = rot;
  state.counters["trans_err_cm"] = trans;
  state.counters["loss_px"] = loss;
  state.counters["truth_loss_px"] = truth_loss;
}
BENCHMARK(BM_DefaultRun)->Arg(2)->ArgName("threads")->Unit(benchmark::kSecond)->Iterations(1);

void BM_QualityAfterRun(benchmark::State& state) {
  const auto& pairs = benchPairs(true);
  CalibrationConfig config;
  config.num_threads = static_cast<int>(state.range(0));
  const CalibrationResult r = calibrate(test_support::fieldsafeCamera(true), pairs, config);
  QualityConfig quality;  // defaults: 100 resamples
  quality.uncertainty.num_threads = config.num_threads;
  double verdict = 0, max_rot = 0;
  for (auto _ : state) {
    const QualityAssessment q =
        assessQuality(test_support::fieldsafeCamera(true), pairs, r, quality, config.behind_camera_penalty_c1);
    verdict = static_cast<double>(q.verdict.verdict);
    max_rot = q.uncertainty ? q.uncertainty->rotation_deg.maxCoeff() : 0.0;
  }
  state.counters["resamples"] = quality.uncertainty.resamples;
  state.counters["max_rot_halfwidth_deg"] = max_rot;
  state.counters["verdict"] = verdict;  // 0 good, 1 usable, 2 collect_more
}
BENCHMARK(BM_QualityAfterRun)->Arg(2)->ArgName("threads")->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
