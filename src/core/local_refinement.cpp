#include "thermal_lidar_calibration/core/local_refinement.hpp"

#include "thermal_lidar_calibration/core/pattern_search.hpp"

namespace thermal_lidar_calibration {
namespace {

// The search runs on (r, s) with s = R pivot + t, the camera-frame position of the pivot (the
// data's centroid), instead of (r, t): a rotation then turns the cloud about its own centre
// rather than about the LiDAR, which is metres away, so rotation and translation steps no
// longer undo each other along a long diagonal valley.
Eigen::VectorXd toVector(const Extrinsic& e, const Eigen::Vector3d& pivot) {
  Eigen::VectorXd v(6);
  v << e.rotation_vector, e.rotationMatrix() * pivot + e.translation;
  return v;
}

Extrinsic fromVector(const Eigen::VectorXd& v, const Eigen::Vector3d& pivot) {
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
  // A camera turn: pivot at the camera centre (in the LiDAR frame, -R^T t), where s = 0; a
  // search over r alone, s held, then turns the camera about its own centre. A camera shift:
  // r held, s (so t) searched.
  const bool turn_only = freedom_ == RefineFreedom::kCameraTurn;
  const Eigen::Vector3d pivot =
      turn_only ? Eigen::Vector3d(-(start.rotationMatrix().transpose() * start.translation))
                : loss_.centroid(pairs);
  PatternSearchConfig search;
  search.initial_step.resize(6);
  search.initial_step << Eigen::Vector3d::Constant(config_.initial_step_rot_rad),
      Eigen::Vector3d::Constant(config_.initial_step_trans_m);
  search.min_step.resize(6);
  search.min_step << Eigen::Vector3d::Constant(config_.min_step_rot_rad),
      Eigen::Vector3d::Constant(config_.min_step_trans_m);
  search.first = freedom_ == RefineFreedom::kCameraShift ? 3 : 0;
  search.last = turn_only ? 3 : 6;
  search.max_evaluations = config_.max_evaluations;
  std::vector<Extrinsic> candidates;
  const BatchLoss batch = [&](const std::vector<Eigen::VectorXd>& points, std::vector<double>& losses) {
    candidates.clear();
    for (const Eigen::VectorXd& v : points) candidates.push_back(fromVector(v, pivot));
    loss_.lossBatch(candidates, pairs, losses, threads_);
  };
  SearchCallback on_iteration;
  if (callback) {
    on_iteration = [&](int iteration, double loss, const Eigen::VectorXd& x, std::uint64_t evaluations) {
      return callback(iteration, loss, fromVector(x, pivot), evaluations);
    };
  }
  const PatternSearchOutcome found = patternSearch(toVector(start, pivot), search, batch, on_iteration);
  RefineOutcome out;
  out.best = fromVector(found.best, pivot);
  out.loss = found.loss;
  out.iterations = found.iterations;
  out.evaluations = found.evaluations;
  out.converged = found.converged;
  out.stopped = found.stopped;
  return out;
}

}  // namespace thermal_lidar_calibration
