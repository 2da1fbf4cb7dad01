#pragma once
// The Wilcoxon signed-rank test, one-sided: do paired differences tend to be positive?
// Distribution-free (only symmetry about zero under the null), so a few pairs with a huge
// difference, such as a mismatched pair in a drift window, weigh by their rank, not their size.

#include <cstddef>
#include <vector>

namespace thermal_lidar_calibration {

struct SignedRankResult {
  std::size_t n = 0;            // non-zero differences used
  double rank_sum_positive = 0; // W+: sum of the ranks of |d| over the positive d
  double p_value = 1.0;         // P(W+ >= observed) under the null; 1 when n == 0
};

// Exact p-value from the permutation distribution of the (mid-)ranks, conditional on ties;
// zero differences (|d| <= zero_tolerance) are dropped (Wilcoxon's rule).
SignedRankResult signedRankTestGreater(const std::vector<double>& differences,
                                       double zero_tolerance = 0.0);

// Two-sided: do the differences tend away from zero, either way? p = twice the smaller of the
// two one-sided p-values, at most 1 (rank_sum_positive as above).
SignedRankResult signedRankTestTwoSided(const std::vector<double>& differences,
                                        double zero_tolerance = 0.0);

// The Hodges-Lehmann estimate of the centre the signed-rank test is about: the median of the
// Walsh averages (d_i + d_j) / 2, i <= j (non-finite values dropped; 0 when none is left).
// Robust like the median (a mismatched pair's value weighs like any other), nearly as precise
// as the mean on well-behaved data.
double hodgesLehmann(const std::vector<double>& values);

}  // namespace thermal_lidar_calibration
