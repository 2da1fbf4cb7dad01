#pragma once
// Algorithm 1 of the paper, as written: a population of Individuals {t, r, loss, prob}; an
// initial population of c2 * N_pop drawn uniformly from the intervals (kept only if some pair
// projects >= 50 % of its points into the image); from the second generation on, the N_pop best;
// selection probabilities (Eq. 4-5); elitism; crossover (Eq. 6-7, alpha ~ U(0.5, 1), the better
// parent weighted by alpha); mutation by uniform noise in +-sigma.

#include "thermal_lidar_calibration/core/calibration_config.hpp"
#include "thermal_lidar_calibration/core/extrinsic.hpp"
#include "thermal_lidar_calibration/core/loss.hpp"
#include "thermal_lidar_calibration/core/random.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <functional>
#include <vector>

namespace thermal_lidar_calibration {

struct Individual {
  Eigen::Vector3d t = Eigen::Vector3d::Zero();  // translation, m
  Eigen::Vector3d r = Eigen::Vector3d::Zero();  // Rodrigues rotation vector, rad
  double loss = 0.0;                            // Eq. (3) on the optimizer's pairs
  double prob = 0.0;                            // selection probability, Eq. (5)
  bool evaluated = false;  // elites keep their loss: re-evaluating gives the same number

  Extrinsic extrinsic() const { return Extrinsic{r, t}; }
};

struct EvolutionOutcome {
  Extrinsic best;
  double best_loss = 0.0;
  int generations = 0;
  std::uint64_t evaluations = 0;  // Eq. (3) evaluations in this run
  bool stopped = false;
};

// Called after each generation's losses are known; return false to stop early.
using GenerationCallback =
    std::function<bool(int generation, double best_loss, const Extrinsic& best,
                       std::uint64_t evaluations)>;

class EvolutionaryOptimizer {
 public:
  // `loss` must outlive the optimizer. threads: 0 = all cores (results do not depend on it).
  EvolutionaryOptimizer(const LossEvaluator& loss, EvolutionConfig config, int threads);

  EvolutionOutcome run(const std::vector<std::size_t>& pairs, Rng& rng,
                       const GenerationCallback& callback = {}) const;

  // Exposed for tests.
  std::vector<Individual> initialPopulation(const std::vector<std::size_t>& pairs, Rng& rng) const;
  static void assignSelectionProbabilities(std::vector<Individual>& population);

 private:
  std::uint64_t evaluate(std::vector<Individual>& population,
                         const std::vector<std::size_t>& pairs) const;
  std::vector<Individual> nextGeneration(const std::vector<Individual>& population,
                                         Rng& rng) const;

  const LossEvaluator& loss_;
  EvolutionConfig config_;
  int threads_;
};

}  // namespace thermal_lidar_calibration
