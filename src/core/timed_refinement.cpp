#include "thermal_lidar_calibration/core/timed_refinement.hpp"

#include "thermal_lidar_calibration/core/pattern_search.hpp"

#include <limits>
#include <map>
#include <stdexcept>

namespace thermal_lidar_calibration {
namespace {

// (r, s, delta) with s = R pivot + t, as LocalRefinement searches (local_refinement.cpp says why).
Eigen::VectorXd toVector(const Extrinsic& e, double delta, const Eigen::Vector3d& pivot) {
  Eigen::VectorXd v(7);
  v << e.rotation_vector, e.rotationMatrix() * pivot + e.translation, delta;
  return v;
}

Extrinsic fromVector(const Eigen::VectorXd& v, const Eigen::Vector3d& pivot) {
  Extrinsic e{v.head<3>(), Eigen::Vector3d::Zero()};
  e.translation = v.segment<3>(3) - e.rotationMatrix() * pivot;
  return e;
}

}  // namespace

TimedRefinement::TimedRefinement(const LossEvaluator& loss, RefineConfig refine, TimeOffsetConfig timing,
                                 int threads)
    : loss_(loss), refine_(refine), timing_(timing), threads_(threads) {
  refine_.validate();
  timing_.validate();
  if (!loss_.config().time_offset_s) {
    throw std::invalid_argument("timed refinement: the loss has no time offset to move points with");
  }
}

TimedRefineOutcome TimedRefinement::run(const Extrinsic& start, double start_offset_s,
                                        const std::vector<std::size_t>& pairs,
                                        const RefineCallback& callback) const {
  const double base_offset = *loss_.config().time_offset_s;
  const Eigen::Vector3d pivot = loss_.centroid(pairs);
  PatternSearchConfig search;
  search.initial_step.resize(7);
  search.initial_step << Eigen::Vector3d::Constant(refine_.initial_step_rot_rad),
      Eigen::Vector3d::Constant(refine_.initial_step_trans_m), timing_.initial_step_s;
  search.min_step.resize(7);
  search.min_step << Eigen::Vector3d::Constant(refine_.min_step_rot_rad),
      Eigen::Vector3d::Constant(refine_.min_step_trans_m), timing_.min_step_s;
  search.max_evaluations = refine_.max_evaluations;

  // One evaluator per delta the search visits; most probes share the current delta, so the few
  // most recent are kept (a pattern move visits each delta once).
  std::map<double, LossEvaluator> at_offset;
  std::vector<double> visited;
  const auto evaluator = [&](double delta) -> const LossEvaluator& {
    if (delta == base_offset) return loss_;
    auto it = at_offset.find(delta);
    if (it != at_offset.end()) return it->second;
    if (visited.size() >= 4) {
      at_offset.erase(visited.front());
      visited.erase(visited.begin());
    }
    visited.push_back(delta);
    return at_offset.emplace(delta, loss_.withTimeOffset(delta)).first->second;
  };
  const BatchLoss batch = [&](const std::vector<Eigen::VectorXd>& points, std::vector<double>& losses) {
    losses.assign(points.size(), std::numeric_limits<double>::infinity());
    std::map<double, std::vector<std::size_t>> by_offset;
    for (std::size_t i = 0; i < points.size(); ++i) {
      // Outside the searched range the loss is not defined: the search must not go there.
      if (std::abs(points[i][6]) <= timing_.max_s) by_offset[points[i][6]].push_back(i);
    }
    std::vector<Extrinsic> candidates;
    std::vector<double> out;
    for (const auto& [delta, indices] : by_offset) {
      candidates.clear();
      for (std::size_t i : indices) candidates.push_back(fromVector(points[i], pivot));
      evaluator(delta).lossBatch(candidates, pairs, out, threads_);
      for (std::size_t k = 0; k < indices.size(); ++k) losses[indices[k]] = out[k];
    }
  };
  SearchCallback on_iteration;
  if (callback) {
    on_iteration = [&](int iteration, double loss, const Eigen::VectorXd& x, std::uint64_t evaluations) {
      return callback(iteration, loss, fromVector(x, pivot), evaluations);
    };
  }
  const PatternSearchOutcome found =
      patternSearch(toVector(start, start_offset_s, pivot), search, batch, on_iteration);
  TimedRefineOutcome out;
  out.best = fromVector(found.best, pivot);
  out.time_offset_s = found.best[6];
  out.loss = found.loss;
  out.iterations = found.iterations;
  out.evaluations = found.evaluations;
  out.converged = found.converged;
  out.stopped = found.stopped;
  return out;
}

}  // namespace thermal_lidar_calibration
