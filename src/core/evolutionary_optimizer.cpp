#include "thermal_lidar_calibration/core/evolutionary_optimizer.hpp"

#include "threads.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace thermal_lidar_calibration {
namespace {

// Draws are made in fixed-size batches from the single RNG stream and accepted in draw order, so
// the initial population does not depend on the thread count that checks them.
constexpr std::size_t kDrawBatch = 256;
// Give up (with an explanation) rather than loop forever on data no random pose can see.
constexpr std::size_t kMaxDrawsPerIndividual = 2000;

std::size_t fractionOf(double fraction, std::size_t n) {
  return static_cast<std::size_t>(std::floor(fraction * static_cast<double>(n) + 1e-9));
}

void sortByLoss(std::vector<Individual>& population) {
  std::stable_sort(population.begin(), population.end(),
                   [](const Individual& a, const Individual& b) { return a.loss < b.loss; });
}

// Roulette-wheel draw on the cumulative selection probabilities.
std::size_t drawIndex(const std::vector<double>& cumulative, Rng& rng) {
  const double x = rng.uniform01() * cumulative.back();
  const auto it = std::upper_bound(cumulative.begin(), cumulative.end(), x);
  return std::min(static_cast<std::size_t>(it - cumulative.begin()), cumulative.size() - 1);
}

}  // namespace

EvolutionaryOptimizer::EvolutionaryOptimizer(const LossEvaluator& loss, EvolutionConfig config,
                                             int threads)
    : loss_(loss), config_(config), threads_(threads) {
  config_.validate();
}

std::vector<Individual> EvolutionaryOptimizer::initialPopulation(
    const std::vector<std::size_t>& pairs, Rng& rng) const {
  const std::size_t target = static_cast<std::size_t>(config_.initial_population_factor) *
                             static_cast<std::size_t>(config_.population_size);
  const std::size_t max_draws = kMaxDrawsPerIndividual * target;
  std::vector<Individual> population;
  population.reserve(target);
  std::vector<Individual> batch(kDrawBatch);
  std::vector<char> accepted(kDrawBatch);
  std::size_t draws = 0;
  const double ri = config_.rotation_interval_rad, ti = config_.translation_interval_m;
  while (population.size() < target) {
    if (draws >= max_draws) {
      throw std::invalid_argument(
          "initial population: after " + std::to_string(draws) + " random poses only " +
          std::to_string(population.size()) + " of " + std::to_string(target) +
          " projected at least " + std::to_string(config_.min_inside_fraction) +
          " of some pair's points into the image; check the camera model, that the clusters are "
          "in the LiDAR frame, and rotation_interval_rad / translation_interval_m");
    }
    for (Individual& ind : batch) {
      for (int k = 0; k < 3; ++k) ind.t[k] = rng.uniform(-ti, ti);
      for (int k = 0; k < 3; ++k) ind.r[k] = rng.uniform(-ri, ri);
    }
    draws += kDrawBatch;
#pragma omp parallel for schedule(static) num_threads(resolveThreads(threads_))
    for (int i = 0; i < static_cast<int>(kDrawBatch); ++i) {
      accepted[i] = loss_.somePairInside(pairs, batch[i].extrinsic(), config_.min_inside_fraction);
    }
    for (std::size_t i = 0; i < kDrawBatch && population.size() < target; ++i) {
      if (accepted[i]) population.push_back(batch[i]);
    }
  }
  return population;
}

void EvolutionaryOptimizer::assignSelectionProbabilities(std::vector<Individual>& population) {
  const double n = static_cast<double>(population.size());
  double loss_sum = 0.0;
  for (const Individual& ind : population) loss_sum += ind.loss;
  // Eq. (4): score = 1 - loss / sum(loss); Eq. (5): prob = score / sum(score). When the formula
  // is undefined (all losses zero, or a single individual) every individual is equally likely.
  double score_sum = 0.0;
  if (loss_sum > 0.0 && std::isfinite(loss_sum)) {
    for (Individual& ind : population) {
      ind.prob = 1.0 - ind.loss / loss_sum;
      score_sum += ind.prob;
    }
  }
  if (!(score_sum > 0.0) || !std::isfinite(score_sum)) {
    for (Individual& ind : population) ind.prob = 1.0 / n;
    return;
  }
  for (Individual& ind : population) ind.prob /= score_sum;
}

std::uint64_t EvolutionaryOptimizer::evaluate(std::vector<Individual>& population,
                                              const std::vector<std::size_t>& pairs) const {
  std::vector<std::size_t> todo;
  std::vector<Extrinsic> candidates;
  for (std::size_t i = 0; i < population.size(); ++i) {
    if (!population[i].evaluated) {
      todo.push_back(i);
      candidates.push_back(population[i].extrinsic());
    }
  }
  if (todo.empty()) return 0;
  std::vector<double> losses;
  loss_.lossBatch(candidates, pairs, losses, threads_);
  for (std::size_t k = 0; k < todo.size(); ++k) {
    population[todo[k]].loss = losses[k];
    population[todo[k]].evaluated = true;
  }
  return todo.size();
}

std::vector<Individual> EvolutionaryOptimizer::nextGeneration(
    const std::vector<Individual>& population, Rng& rng) const {
  const std::size_t n = population.size();
  const std::size_t n_elite = std::min(n, fractionOf(config_.elite_fraction, n));
  const std::size_t n_cross = std::min(n - n_elite, fractionOf(config_.crossover_fraction, n));
  const std::size_t n_mutation = n - n_elite - n_cross;

  std::vector<double> cumulative(n);
  double acc = 0.0;
  for (std::size_t i = 0; i < n; ++i) cumulative[i] = acc += population[i].prob;

  std::vector<Individual> next;
  next.reserve(n);
  // Line 19: the population is sorted by loss, so its head is the elite.
  next.insert(next.end(), population.begin(), population.begin() + n_elite);
  // Lines 20-21: crossover of pairs drawn with replacement (Eq. 6-7).
  for (std::size_t k = 0; k < n_cross; ++k) {
    const Individual& a = population[drawIndex(cumulative, rng)];
    const Individual& b = population[drawIndex(cumulative, rng)];
    const Individual& one = a.loss <= b.loss ? a : b;  // the better parent gets alpha
    const Individual& two = a.loss <= b.loss ? b : a;
    const double alpha = rng.uniform(0.5, 1.0);
    Individual child;
    child.r = alpha * one.r + (1.0 - alpha) * two.r;
    child.t = alpha * one.t + (1.0 - alpha) * two.t;
    next.push_back(child);
  }
  // Lines 22-23: mutation of individuals drawn with replacement.
  for (std::size_t k = 0; k < n_mutation; ++k) {
    Individual child = population[drawIndex(cumulative, rng)];
    for (int j = 0; j < 3; ++j) child.r[j] += rng.uniform(-config_.sigma_rot_rad, config_.sigma_rot_rad);
    for (int j = 0; j < 3; ++j) child.t[j] += rng.uniform(-config_.sigma_trans_m, config_.sigma_trans_m);
    child.evaluated = false;
    next.push_back(child);
  }
  return next;
}

EvolutionOutcome EvolutionaryOptimizer::run(const std::vector<std::size_t>& pairs, Rng& rng,
                                            const GenerationCallback& callback) const {
  if (pairs.empty()) throw std::invalid_argument("Algorithm 1: no pairs to fit");
  EvolutionOutcome outcome;
  std::vector<Individual> population = initialPopulation(pairs, rng);
  const std::size_t n_pop = static_cast<std::size_t>(config_.population_size);
  for (int generation = 1; generation <= config_.max_iterations; ++generation) {
    outcome.evaluations += evaluate(population, pairs);
    sortByLoss(population);
    // Lines 10-12: from the second generation on, only the N_pop best go on.
    if (generation > 1 && population.size() > n_pop) population.resize(n_pop);
    assignSelectionProbabilities(population);
    outcome.generations = generation;
    if (callback && !callback(generation, population.front().loss,
                              population.front().extrinsic(), outcome.evaluations)) {
      outcome.stopped = true;
      break;
    }
    population = nextGeneration(population, rng);
  }
  // Line 26 returns the best of the final population: its new members need their loss first.
  outcome.evaluations += evaluate(population, pairs);
  sortByLoss(population);
  outcome.best = population.front().extrinsic();
  outcome.best_loss = population.front().loss;
  return outcome;
}

}  // namespace thermal_lidar_calibration
