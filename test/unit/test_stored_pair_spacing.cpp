// ~resume with the drive played again: live frames next to a stored pair are passed over as the
// skip rule passed them over in the stored session (stored_pair_spacing.hpp).

#include "thermal_lidar_calibration/core/stored_pair_spacing.hpp"

#include <gtest/gtest.h>

namespace tlc = thermal_lidar_calibration;

TEST(StoredPairSpacing, FramesWithinTheSkipRuleOfAStoredPairArePassedOver) {
  // 10 Hz, stored pairs at frames 0, 4, 9, 20 (skip 3), stamps with a little jitter.
  const tlc::StoredPairSpacing spacing({{100.0, 0}, {100.401, 4}, {100.9, 9}, {102.0, 20}}, 3);
  ASSERT_TRUE(spacing.framePeriodS().has_value());
  EXPECT_NEAR(*spacing.framePeriodS(), 0.1, 0.001);
  for (const double t : {100.1, 100.2, 100.3, 100.5, 100.6, 100.7, 100.8, 101.0, 101.2, 101.7, 101.8, 102.3}) {
    EXPECT_TRUE(spacing.tooClose(t)) << t;
  }
  for (const double t : {101.3, 101.4, 101.5, 102.4, 102.5, 99.5}) EXPECT_FALSE(spacing.tooClose(t)) << t;
  EXPECT_FALSE(spacing.tooClose(100.0));  // the stored frame itself is not its own neighbour
}

TEST(StoredPairSpacing, WithoutFrameNumbersOrWithoutTheRuleNothingIsPassedOver) {
  EXPECT_FALSE(tlc::StoredPairSpacing({{100.0, std::nullopt}, {100.4, std::nullopt}}, 3).tooClose(100.1));
  EXPECT_FALSE(tlc::StoredPairSpacing({{100.0, 0}}, 3).tooClose(100.1));          // one pair: no period
  EXPECT_FALSE(tlc::StoredPairSpacing({{100.0, 0}, {100.4, 4}}, 0).tooClose(100.1));  // skip rule off
  EXPECT_FALSE(tlc::StoredPairSpacing({}, 3).tooClose(100.1));
}
