#include "thermal_lidar_calibration/core/local_refinement.hpp"

#include <array>

namespace thermal_lidar_calibration {
namespace {

using Vector6 = Eigen::Matrix<double, 6, 1>;

// The search runs on (r, s) with s = R pivot + t, the camera-frame position of the pivot (the
// data's centroid), instead of (r, t): a rotation then turns the cloud about its own centre
// rather than about the LiDAR, which is metres away, so rotation and translation steps no
// longer undo each other along a long diagonal valley.
Vector6 toVector(const Extrinsic& e, const Eigen::Vector3d& pivot) {
  Vector6 v;
  v << e.rotation_vector, e.rotationMatrix() * pivot + e.translation;
  return v;
}

Extrinsic fromVector(const Vector6& v, const Eigen::Vector3d& pivot) {
  Extrinsic e{v.head<3>(), Eigen::Vector3d::Zero()};
  e.translation = v.tail<3>() - e.rotationMatrix() * pivot;
  return e;
}

}  // namespace

LocalRefinement::LocalRefinement(const LossEvaluator& loss, RefineConfig config, int threads,
                                 RefineFreedom freedom)
    : loss_(loss), config_(config), threads_(threads), freedom_(freedom) {
  config_.validate();
}

RefineOutcome LocalRefinement::run(const Extrinsic& start, const std::vector<std::size_t>& pairs,
                                   const RefineCallback& callback) const {
  RefineOutcome out;
  // A camera turn: pivot at the camera centre (in the LiDAR frame, -R^T t), where s = 0; a
  // search over r alone, s held, then turns the camera about its own centre. A camera shift:
  // r held, s (so t) searched.
  const bool turn_only = freedom_ == RefineFreedom::kCameraTurn;
  const Eigen::Vector3d pivot =
      turn_only ? Eigen::Vector3d(-(start.rotationMatrix().transpose() * start.translation))
                : loss_.centroid(pairs);
  const int first = freedom_ == RefineFreedom::kCameraShift ? 3 : 0;
  const int last = turn_only ? 3 : 6;
  Vector6 x = toVector(start, pivot);
  Vector6 step;
  step << Eigen::Vector3d::Constant(config_.initial_step_rot_rad),
      Eigen::Vector3d::Constant(config_.initial_step_trans_m);
  const Vector6 min_step = (Vector6() << Eigen::Vector3d::Constant(config_.min_step_rot_rad),
                            Eigen::Vector3d::Constant(config_.min_step_trans_m))
                               .finished();
  std::vector<double> losses;
  auto evaluate = [&](const std::vector<Extrinsic>& candidates) {
    loss_.lossBatch(candidates, pairs, losses, threads_);
    out.evaluations += candidates.size();
  };
  evaluate({fromVector(x, pivot)});
  double fx = losses[0];

  // A pattern search along the parameter axes can stall in a valley that runs diagonally
  // (rotation about the vertical axis against sideways translation, for example): when the
  // steps have shrunk, restart from the optimum with the initial steps until a whole restart
  // gains less than kRestartGain.
  constexpr double kRestartGain = 1e-6;
  constexpr int kMaxRestarts = 20;
  const Vector6 initial_step = step;
  double restart_from = fx;
  int restarts = 0;
  while (static_cast<int>(out.evaluations) < config_.max_evaluations) {
    if ((step.array() < min_step.array()).all()) {
      if (restarts < kMaxRestarts && restart_from - fx > kRestartGain) {
        ++restarts;
        restart_from = fx;
        step = initial_step;
        continue;
      }
      out.converged = true;
      break;
    }
    ++out.iterations;
    // Exploratory probes: +-step along each parameter, evaluated together (one parallel batch).
    std::vector<Extrinsic> probes;
    for (int k = first; k < last; ++k) {
      for (double sign : {1.0, -1.0}) {
        Vector6 y = x;
        y[k] += sign * step[k];
        probes.push_back(fromVector(y, pivot));
      }
    }
    evaluate(probes);
    Vector6 combined = Vector6::Zero();
    int best_probe = -1;
    double best_loss = fx;
    for (int k = first; k < last; ++k) {
      const int probe = 2 * (k - first);
      const double plus = losses[probe], minus = losses[probe + 1];
      if (std::min(plus, minus) < fx) combined[k] = plus <= minus ? step[k] : -step[k];
      for (int j = 0; j < 2; ++j) {
        if (losses[probe + j] < best_loss) {
          best_loss = losses[probe + j];
          best_probe = probe + j;
        }
      }
    }
    if (best_probe < 0) {
      step *= 0.5;  // nothing improves at this scale: look closer
    } else {
      // Take the better of the best single probe and the move along every improving axis, then
      // keep moving in that direction while it pays (the pattern move of Hooke-Jeeves).
      Vector6 direction = toVector(probes[best_probe], pivot) - x;
      evaluate({fromVector(x + combined, pivot)});
      if (losses[0] < best_loss) {
        best_loss = losses[0];
        direction = combined;
      }
      x += direction;
      fx = best_loss;
      while (static_cast<int>(out.evaluations) < config_.max_evaluations) {
        evaluate({fromVector(x + direction, pivot)});
        if (!(losses[0] < fx)) break;
        x += direction;
        fx = losses[0];
      }
    }
    if (callback && !callback(out.iterations, fx, fromVector(x, pivot), out.evaluations)) {
      out.stopped = true;
      break;
    }
  }
  out.best = fromVector(x, pivot);
  out.loss = fx;
  return out;
}

}  // namespace thermal_lidar_calibration
