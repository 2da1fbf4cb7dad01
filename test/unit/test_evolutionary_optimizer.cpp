// Algorithm 1: selection probabilities, the initial population rule, recovery of a known
// extrinsic with the paper's defaults, and identical results for 1 and 2 threads.
#include "thermal_lidar_calibration/core/evolutionary_optimizer.hpp"

#include "../support/synthetic_pairs.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace thermal_lidar_calibration;
using test_support::fieldsafeCamera;
using test_support::fieldsafeTruth;

namespace {
constexpr double kDeg = M_PI / 180.0;

std::vector<std::size_t> allPairs(std::size_t n) {
  std::vector<std::size_t> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = i;
  return v;
}
}  // namespace

TEST(SelectionProbability, FollowsEquations4And5) {
  std::vector<Individual> population(3);
  population[0].loss = 1;
  population[1].loss = 2;
  population[2].loss = 3;
  EvolutionaryOptimizer::assignSelectionProbabilities(population);
  // scores 5/6, 4/6, 3/6 sum to 2.
  EXPECT_DOUBLE_EQ(population[0].prob, 5.0 / 12.0);
  EXPECT_DOUBLE_EQ(population[1].prob, 4.0 / 12.0);
  EXPECT_DOUBLE_EQ(population[2].prob, 3.0 / 12.0);
}

TEST(SelectionProbability, AllZeroLossesAreEquallyLikely) {
  std::vector<Individual> population(4);
  EvolutionaryOptimizer::assignSelectionProbabilities(population);
  for (const Individual& i : population) EXPECT_DOUBLE_EQ(i.prob, 0.25);
}

TEST(InitialPopulation, HasC2TimesNpopIndividualsThatEachSeeHalfOfSomePair) {
  const CameraModel camera = fieldsafeCamera();
  test_support::SyntheticPairsOptions o;
  o.pairs = 8;
  const auto pairs = test_support::makeSyntheticPairs(camera, fieldsafeTruth(), o);
  const LossEvaluator loss(camera, pairs, LossConfig{});
  EvolutionConfig config;
  config.population_size = 40;
  config.initial_population_factor = 5;
  const EvolutionaryOptimizer optimizer(loss, config, 2);
  Rng rng(3);
  const auto population = optimizer.initialPopulation(allPairs(pairs.size()), rng);
  ASSERT_EQ(population.size(), 200u);
  for (const Individual& ind : population) {
    EXPECT_LE(ind.r.cwiseAbs().maxCoeff(), 3.5);
    EXPECT_LE(ind.t.cwiseAbs().maxCoeff(), 1.0);
    double best = 0;
    for (std::size_t p = 0; p < pairs.size(); ++p) best = std::max(best, loss.insideFraction(p, ind.extrinsic()));
    EXPECT_GE(best, 0.5);
  }
}

TEST(Algorithm1, RecoversTheTruthFromSyntheticPairsWithThePapersDefaults) {
  const CameraModel camera = fieldsafeCamera();
  const Extrinsic truth = fieldsafeTruth();
  test_support::SyntheticPairsOptions o;
  o.pairs = 20;
  const auto pairs = test_support::makeSyntheticPairs(camera, truth, o);
  const LossEvaluator loss(camera, pairs, LossConfig{});
  const EvolutionaryOptimizer optimizer(loss, EvolutionConfig{}, 0);  // Table 1
  Rng rng(11);
  int last_generation = 0;
  double last_best = 1e300;
  bool monotone = true;
  const EvolutionOutcome out =
      optimizer.run(allPairs(pairs.size()), rng, [&](int g, double best, const Extrinsic&, std::uint64_t) {
        monotone = monotone && best <= last_best;  // elitism: the best never gets worse
        last_best = best;
        last_generation = g;
        return true;
      });
  EXPECT_TRUE(monotone);
  EXPECT_EQ(last_generation, 400);
  EXPECT_LT(rotationErrorRad(out.best, truth), 0.5 * kDeg);
  EXPECT_LT(translationErrorM(out.best, truth), 0.08);
  EXPECT_LE(out.best_loss, loss.loss(truth) + 0.5);
}

TEST(Algorithm1, SameSeedGivesTheIdenticalResultWithOneAndTwoThreads) {
  const CameraModel camera = fieldsafeCamera();
  test_support::SyntheticPairsOptions o;
  o.pairs = 10;
  const auto pairs = test_support::makeSyntheticPairs(camera, fieldsafeTruth(), o);
  const LossEvaluator loss(camera, pairs, LossConfig{});
  EvolutionConfig config;
  config.population_size = 120;
  config.max_iterations = 60;
  EvolutionOutcome results[2];
  for (int threads : {1, 2}) {
    const EvolutionaryOptimizer optimizer(loss, config, threads);
    Rng rng(42);
    results[threads - 1] = optimizer.run(allPairs(pairs.size()), rng);
  }
  EXPECT_EQ(results[0].best_loss, results[1].best_loss);
  EXPECT_EQ(results[0].best.rotation_vector, results[1].best.rotation_vector);
  EXPECT_EQ(results[0].best.translation, results[1].best.translation);
}

TEST(Algorithm1, StopsWhenTheCallbackAsks) {
  const CameraModel camera = fieldsafeCamera();
  test_support::SyntheticPairsOptions o;
  o.pairs = 5;
  const auto pairs = test_support::makeSyntheticPairs(camera, fieldsafeTruth(), o);
  const LossEvaluator loss(camera, pairs, LossConfig{});
  EvolutionConfig config;
  config.population_size = 50;
  const EvolutionaryOptimizer optimizer(loss, config, 1);
  Rng rng(1);
  const EvolutionOutcome out = optimizer.run(allPairs(pairs.size()), rng,
                                             [](int g, double, const Extrinsic&, std::uint64_t) { return g < 3; });
  EXPECT_TRUE(out.stopped);
  EXPECT_EQ(out.generations, 3);
}
