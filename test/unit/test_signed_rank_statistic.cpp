// The one-sided Wilcoxon signed-rank test of the drift watch, against p-values worked out by
// hand from the permutation distribution.
#include "thermal_lidar_calibration/core/signed_rank_statistic.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace thermal_lidar_calibration;

TEST(SignedRankTest, AllPositiveIsTheSmallestPossiblePValue) {
  // Every one of the 2^n sign patterns is equally likely; only "all +" reaches the maximum.
  const SignedRankResult r = signedRankTestGreater({0.3, 1.2, 2.0});
  EXPECT_EQ(r.n, 3u);
  EXPECT_DOUBLE_EQ(r.rank_sum_positive, 6.0);
  EXPECT_DOUBLE_EQ(r.p_value, 1.0 / 8.0);
  std::vector<double> twenty(20);
  for (int i = 0; i < 20; ++i) twenty[i] = 0.1 * (i + 1);
  EXPECT_NEAR(signedRankTestGreater(twenty).p_value, std::ldexp(1.0, -20), 1e-18);
}

TEST(SignedRankTest, HandWorkedExample) {
  // Ranks of |d|: 1 (-1), 2 (+2), 3 (+3): W+ = 5. Sums over the 8 sign patterns:
  // 0, 1, 2, 3, 3, 4, 5, 6 -> P(W+ >= 5) = 2/8.
  const SignedRankResult r = signedRankTestGreater({-1.0, 2.0, 3.0});
  EXPECT_DOUBLE_EQ(r.rank_sum_positive, 5.0);
  EXPECT_DOUBLE_EQ(r.p_value, 0.25);
  // Mirror image: W+ = 1 -> P(W+ >= 1) = 7/8.
  EXPECT_DOUBLE_EQ(signedRankTestGreater({1.0, -2.0, -3.0}).p_value, 7.0 / 8.0);
}

TEST(SignedRankTest, SizesMatterOnlyThroughTheirRanks) {
  // A huge difference (a mismatched pair) weighs like any other top rank.
  EXPECT_DOUBLE_EQ(signedRankTestGreater({-1.0, 2.0, 3.0}).p_value,
                   signedRankTestGreater({-1.0, 2.0, 3000.0}).p_value);
}

TEST(SignedRankTest, ZerosAreDroppedAndTiesShareTheirRanks) {
  const SignedRankResult zeros = signedRankTestGreater({0.0, 0.0, 1.0, 2.0}, 0.0);
  EXPECT_EQ(zeros.n, 2u);
  EXPECT_DOUBLE_EQ(zeros.p_value, 0.25);
  // |d| = 1, 1, 2: mid-ranks 1.5, 1.5, 3. Signs (-, +, +): W+ = 4.5. Of the 8 patterns the sums
  // are 0, 1.5, 1.5, 3, 3, 4.5, 4.5, 6: P(W+ >= 4.5) = 3/8.
  const SignedRankResult ties = signedRankTestGreater({-1.0, 1.0, 2.0});
  EXPECT_DOUBLE_EQ(ties.rank_sum_positive, 4.5);
  EXPECT_DOUBLE_EQ(ties.p_value, 3.0 / 8.0);
  // Within the tolerance counts as zero.
  EXPECT_EQ(signedRankTestGreater({1e-12, 1.0}, 1e-9).n, 1u);
}

TEST(SignedRankTest, NothingToTestGivesPOne) {
  EXPECT_DOUBLE_EQ(signedRankTestGreater({}).p_value, 1.0);
  EXPECT_DOUBLE_EQ(signedRankTestGreater({0.0, NAN}).p_value, 1.0);
}

TEST(SignedRankTest, SymmetricNullGivesAboutUniformPValues) {
  // Alternating signs with growing sizes: W+ sits near the middle, p near one half.
  std::vector<double> d;
  for (int i = 1; i <= 30; ++i) d.push_back((i % 2 ? 1.0 : -1.0) * i);
  const double p = signedRankTestGreater(d).p_value;
  EXPECT_GT(p, 0.3);
  EXPECT_LT(p, 0.7);
}

TEST(SignedRankTest, TwoSidedIsTwiceTheSmallerTail) {
  // {-1, 2, 3}: P(W+ >= 5) = 2/8, P(W+ <= 5) = 7/8: two-sided 2 * 2/8.
  const SignedRankResult r = signedRankTestTwoSided({-1.0, 2.0, 3.0});
  EXPECT_DOUBLE_EQ(r.rank_sum_positive, 5.0);
  EXPECT_DOUBLE_EQ(r.p_value, 0.5);
  // Either direction alike.
  EXPECT_DOUBLE_EQ(signedRankTestTwoSided({1.0, -2.0, -3.0}).p_value, 0.5);
  std::vector<double> twenty(20);
  for (int i = 0; i < 20; ++i) twenty[i] = -0.1 * (i + 1);
  EXPECT_NEAR(signedRankTestTwoSided(twenty).p_value, std::ldexp(1.0, -19), 1e-18);
  // Never above 1 (the two tails overlap at the middle).
  EXPECT_DOUBLE_EQ(signedRankTestTwoSided({-1.0, 1.0}).p_value, 1.0);
  EXPECT_DOUBLE_EQ(signedRankTestTwoSided({}).p_value, 1.0);
}

TEST(SignedRankTest, HodgesLehmannIsTheMedianOfTheWalshAverages) {
  // Walsh averages of {1, 2, 3}: 1, 1.5, 2, 2, 2.5, 3: median 2.
  EXPECT_DOUBLE_EQ(hodgesLehmann({3.0, 1.0, 2.0}), 2.0);
  // {0, 0, 10}: 0, 0, 0, 5, 5, 10: median (0 + 5) / 2.
  EXPECT_DOUBLE_EQ(hodgesLehmann({0.0, 0.0, 10.0}), 2.5);
  // A wild value moves it little: {1, 2, 3, 1000}: ..., 2.5, 3, ...: (2.5 + 3) / 2.
  EXPECT_DOUBLE_EQ(hodgesLehmann({1.0, 2.0, 3.0, 1000.0}), 2.75);
  EXPECT_DOUBLE_EQ(hodgesLehmann({NAN, 4.0}), 4.0);
  EXPECT_DOUBLE_EQ(hodgesLehmann({}), 0.0);
}
