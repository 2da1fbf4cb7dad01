// FaultThrottle: one warning line per kind of fault and period, counting what it held back
// (issue 12, item 6).

#include "thermal_lidar_calibration/app/runtime/fault_throttle.hpp"

#include <gtest/gtest.h>

namespace tlc = thermal_lidar_calibration;
using Clock = tlc::FaultThrottle::Clock;
using std::chrono::milliseconds;

TEST(FaultThrottle, KindIgnoresNumbers) {
  EXPECT_EQ(tlc::FaultThrottle::kindOf("mask 80x64 does not match camera_info 160x128 at 1600000000.25"),
            "mask #x# does not match camera_info #x# at #");
  EXPECT_EQ(tlc::FaultThrottle::kindOf("stamp 1.6e+09 and -4.5"), "stamp # and #");
  EXPECT_EQ(tlc::FaultThrottle::kindOf("no label field"), "no label field");
  EXPECT_NE(tlc::FaultThrottle::kindOf("no label field"), tlc::FaultThrottle::kindOf("no x field"));
}

TEST(FaultThrottle, OneLinePerKindAndPeriodWithTheCountHeldBack) {
  tlc::FaultThrottle throttle(5.0);
  const Clock::time_point t0 = Clock::now();
  auto first = throttle.admit("mask 80x64 at 1.0", t0);
  ASSERT_TRUE(first.has_value());
  EXPECT_EQ(*first, 0u);
  for (int i = 0; i < 212; ++i) {
    EXPECT_FALSE(throttle.admit("mask " + std::to_string(81 + i) + "x64 at 2.0", t0 + milliseconds(10 * i)));
  }
  // Another kind is not hidden behind the first.
  EXPECT_TRUE(throttle.admit("cloud has no label field", t0 + milliseconds(100)).has_value());
  const auto next = throttle.admit("mask 99x99 at 9.0", t0 + milliseconds(5001));
  ASSERT_TRUE(next.has_value());
  EXPECT_EQ(*next, 212u);
  EXPECT_EQ(throttle.heldBackText(*next), " (and 212 more like it in the last 5 s)");
  EXPECT_EQ(throttle.heldBackText(0), "");
  // The count starts again after each line.
  EXPECT_FALSE(throttle.admit("mask 1x1 at 9.5", t0 + milliseconds(5500)));
  EXPECT_EQ(*throttle.admit("mask 1x1 at 11", t0 + milliseconds(10002)), 1u);
}

// ~fault_log_period_s sets the period: a short one (the bad-message rostest uses one) is said as
// it is, not rounded to whole seconds.
TEST(FaultThrottle, AShortPeriodIsSaidAsItIs) {
  tlc::FaultThrottle throttle(0.5);
  const Clock::time_point t0 = Clock::now();
  ASSERT_TRUE(throttle.admit("mask 80x64", t0).has_value());
  EXPECT_FALSE(throttle.admit("mask 81x64", t0 + milliseconds(499)));
  const auto next = throttle.admit("mask 82x64", t0 + milliseconds(501));
  ASSERT_TRUE(next.has_value());
  EXPECT_EQ(throttle.heldBackText(*next), " (and 1 more like it in the last 0.5 s)");
}
