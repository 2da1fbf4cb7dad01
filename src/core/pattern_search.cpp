#include "thermal_lidar_calibration/core/pattern_search.hpp"

#include <algorithm>
#include <stdexcept>

namespace thermal_lidar_calibration {

namespace {

// Exploratory probes: +-step along each free parameter [first, last), evaluated together.
std::vector<Eigen::VectorXd> exploratoryProbes(const Eigen::VectorXd& x, const Eigen::VectorXd& step,
                                               int first, int last) {
  std::vector<Eigen::VectorXd> probes;
  for (int k = first; k < last; ++k) {
    for (double sign : {1.0, -1.0}) {
      Eigen::VectorXd y = x;
      y[k] += sign * step[k];
      probes.push_back(y);
    }
  }
  return probes;
}

// What the probes' losses say against fx: the move along every improving axis, and the best
// single probe (-1 when none improves) with its loss.
struct ProbeOutcome {
  Eigen::VectorXd combined;
  int best_probe = -1;
  double best_loss = 0.0;
};
ProbeOutcome readProbes(const std::vector<double>& losses, const Eigen::VectorXd& step, double fx,
                        int first, int last) {
  ProbeOutcome out;
  out.combined = Eigen::VectorXd::Zero(step.size());
  out.best_loss = fx;
  for (int k = first; k < last; ++k) {
    const int probe = 2 * (k - first);
    const double plus = losses[probe], minus = losses[probe + 1];
    if (std::min(plus, minus) < fx) out.combined[k] = plus <= minus ? step[k] : -step[k];
    for (int j = 0; j < 2; ++j) {
      if (losses[probe + j] < out.best_loss) {
        out.best_loss = losses[probe + j];
        out.best_probe = probe + j;
      }
    }
  }
  return out;
}

}  // namespace

PatternSearchOutcome patternSearch(const Eigen::VectorXd& start, const PatternSearchConfig& config,
                                   const BatchLoss& loss, const SearchCallback& callback) {
  const int n = static_cast<int>(start.size());
  const int first = config.first;
  const int last = config.last < 0 ? n : config.last;
  if (config.initial_step.size() != n || config.min_step.size() != n || first < 0 || last > n ||
      first >= last) {
    throw std::invalid_argument("pattern search: steps or free parameters do not match the start");
  }
  PatternSearchOutcome out;
  std::vector<double> losses;
  auto evaluate = [&](const std::vector<Eigen::VectorXd>& points) {
    loss(points, losses);
    out.evaluations += points.size();
  };
  Eigen::VectorXd x = start;
  Eigen::VectorXd step = config.initial_step;
  evaluate({x});
  double fx = losses[0];

  constexpr double kRestartGain = 1e-6;
  constexpr int kMaxRestarts = 20;
  double restart_from = fx;
  int restarts = 0;
  const auto below_min = [&] {
    for (int k = 0; k < n; ++k) {
      if (!(step[k] < config.min_step[k])) return false;
    }
    return true;
  };
  while (static_cast<int>(out.evaluations) < config.max_evaluations) {
    if (below_min()) {
      if (restarts < kMaxRestarts && restart_from - fx > kRestartGain) {
        ++restarts;
        restart_from = fx;
        step = config.initial_step;
        continue;
      }
      out.converged = true;
      break;
    }
    ++out.iterations;
    const std::vector<Eigen::VectorXd> probes = exploratoryProbes(x, step, first, last);
    evaluate(probes);
    const ProbeOutcome probed = readProbes(losses, step, fx, first, last);
    const Eigen::VectorXd& combined = probed.combined;
    const int best_probe = probed.best_probe;
    double best_loss = probed.best_loss;
    if (best_probe < 0) {
      step *= 0.5;  // nothing improves at this scale: look closer
    } else {
      // The better of the best single probe and the move along every improving axis, then keep
      // moving in that direction while it pays (the pattern move).
      Eigen::VectorXd direction = probes[best_probe] - x;
      evaluate({x + combined});
      if (losses[0] < best_loss) {
        best_loss = losses[0];
        direction = combined;
      }
      x += direction;
      fx = best_loss;
      while (static_cast<int>(out.evaluations) < config.max_evaluations) {
        evaluate({x + direction});
        if (!(losses[0] < fx)) break;
        x += direction;
        fx = losses[0];
      }
    }
    if (callback && !callback(out.iterations, fx, x, out.evaluations)) {
      out.stopped = true;
      break;
    }
  }
  out.best = x;
  out.loss = fx;
  return out;
}

}  // namespace thermal_lidar_calibration
