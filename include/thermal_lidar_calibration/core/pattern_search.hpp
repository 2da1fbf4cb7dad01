#pragma once
// The derivative-free local search behind the refinement (Hooke-Jeeves style), over any number
// of parameters: +-step probes on each free parameter evaluated as one batch, a combined move
// along every improving axis, the pattern move repeated while it pays, step halving when nothing
// improves, and restarts from the optimum with the initial steps while a whole restart still
// gains (an axis search can stall in a valley that runs diagonally). What the parameters mean is
// the caller's: LocalRefinement searches the pose, TimedRefinement the pose and a time offset.

#include <Eigen/Core>

#include <cstdint>
#include <functional>
#include <vector>

namespace thermal_lidar_calibration {

struct PatternSearchConfig {
  Eigen::VectorXd initial_step;  // per parameter
  Eigen::VectorXd min_step;      // stop when every step is below these
  int first = 0, last = -1;      // free parameters [first, last); last < 0: all
  int max_evaluations = 20000;
};

struct PatternSearchOutcome {
  Eigen::VectorXd best;
  double loss = 0.0;
  int iterations = 0;
  std::uint64_t evaluations = 0;
  bool converged = false;  // steps shrank below the minimum (not stopped by the budget)
  bool stopped = false;    // the callback asked to stop
};

// losses[i] = loss(points[i]); called with the probes of one iteration at once.
using BatchLoss = std::function<void(const std::vector<Eigen::VectorXd>& points, std::vector<double>& losses)>;
// After each iteration; return false to stop.
using SearchCallback = std::function<bool(int iteration, double loss, const Eigen::VectorXd& best,
                                          std::uint64_t evaluations)>;

PatternSearchOutcome patternSearch(const Eigen::VectorXd& start, const PatternSearchConfig& config,
                                   const BatchLoss& loss, const SearchCallback& callback = {});

}  // namespace thermal_lidar_calibration
