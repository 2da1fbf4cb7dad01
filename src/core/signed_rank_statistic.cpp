#include "thermal_lidar_calibration/core/signed_rank_statistic.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace thermal_lidar_calibration {

SignedRankResult signedRankTestGreater(const std::vector<double>& differences,
                                       double zero_tolerance) {
  std::vector<double> d;
  for (double v : differences) {
    if (std::isfinite(v) && std::abs(v) > zero_tolerance) d.push_back(v);
  }
  SignedRankResult out;
  out.n = d.size();
  if (d.empty()) return out;

  // Mid-ranks of |d|, doubled so that tied ranks stay integers (ranks k..m -> k + m).
  std::vector<std::size_t> order(d.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return std::abs(d[a]) < std::abs(d[b]); });
  std::vector<long> doubled_rank(d.size());
  for (std::size_t i = 0; i < order.size();) {
    std::size_t j = i;
    while (j + 1 < order.size() && std::abs(d[order[j + 1]]) == std::abs(d[order[i]])) ++j;
    for (std::size_t k = i; k <= j; ++k) doubled_rank[order[k]] = static_cast<long>(i + j + 2);
    i = j + 1;
  }
  long observed = 0, total = 0;
  for (std::size_t i = 0; i < d.size(); ++i) {
    total += doubled_rank[i];
    if (d[i] > 0) observed += doubled_rank[i];
  }
  out.rank_sum_positive = observed / 2.0;

  // Under the null each rank carries a + sign with probability 1/2 independently: the
  // distribution of the doubled W+ by dynamic programming over the ranks (n <= a few hundred
  // in a drift window, so at most ~1e7 steps).
  std::vector<double> probability(static_cast<std::size_t>(total) + 1, 0.0);
  probability[0] = 1.0;
  long reach = 0;
  for (long r : doubled_rank) {
    for (long s = reach; s >= 0; --s) {
      const double p = probability[static_cast<std::size_t>(s)];
      if (p == 0.0) continue;
      probability[static_cast<std::size_t>(s)] = 0.5 * p;
      probability[static_cast<std::size_t>(s + r)] += 0.5 * p;
    }
    reach += r;
  }
  double tail = 0.0;
  for (long s = observed; s <= total; ++s) tail += probability[static_cast<std::size_t>(s)];
  out.p_value = std::min(1.0, tail);
  return out;
}

SignedRankResult signedRankTestTwoSided(const std::vector<double>& differences,
                                        double zero_tolerance) {
  SignedRankResult out = signedRankTestGreater(differences, zero_tolerance);
  std::vector<double> mirrored(differences.size());
  std::transform(differences.begin(), differences.end(), mirrored.begin(),
                 [](double v) { return -v; });
  const double lower = signedRankTestGreater(mirrored, zero_tolerance).p_value;
  if (out.n > 0) out.p_value = std::min(1.0, 2.0 * std::min(out.p_value, lower));
  return out;
}

double hodgesLehmann(const std::vector<double>& values) {
  std::vector<double> v;
  for (double x : values) {
    if (std::isfinite(x)) v.push_back(x);
  }
  if (v.empty()) return 0.0;
  std::vector<double> walsh;
  walsh.reserve(v.size() * (v.size() + 1) / 2);
  for (std::size_t i = 0; i < v.size(); ++i) {
    for (std::size_t j = i; j < v.size(); ++j) walsh.push_back(0.5 * (v[i] + v[j]));
  }
  const std::size_t mid = walsh.size() / 2;
  std::nth_element(walsh.begin(), walsh.begin() + static_cast<long>(mid), walsh.end());
  const double upper = walsh[mid];
  if (walsh.size() % 2 == 1) return upper;
  const double lower = *std::max_element(walsh.begin(), walsh.begin() + static_cast<long>(mid));
  return 0.5 * (lower + upper);
}

}  // namespace thermal_lidar_calibration
