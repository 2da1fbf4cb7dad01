// The drift watch's verdict from window to window, and where in a window a change is placed.
#include "thermal_lidar_calibration/core/change_point.hpp"
#include "thermal_lidar_calibration/core/drift_state.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

using namespace thermal_lidar_calibration;

TEST(DriftStateMachine, OneChangedWindowWarnsTwoConsecutiveConfirm) {
  DriftStateMachine m(2);
  EXPECT_EQ(m.onTest(false, 1.0), DriftState::kOk);
  EXPECT_EQ(m.onTest(true, 2.0), DriftState::kWarn);
  EXPECT_EQ(m.onTest(true, 3.0), DriftState::kError);
  ASSERT_TRUE(m.firstWarnStamp());
  ASSERT_TRUE(m.firstErrorStamp());
  EXPECT_DOUBLE_EQ(*m.firstWarnStamp(), 2.0);
  EXPECT_DOUBLE_EQ(*m.firstErrorStamp(), 3.0);
}

TEST(DriftStateMachine, AnUnchangedWindowWithdrawsAWarningButNotAnError) {
  DriftStateMachine m(2);
  m.onTest(true, 1.0);
  EXPECT_EQ(m.onTest(false, 2.0), DriftState::kOk);
  EXPECT_EQ(m.consecutiveChanged(), 0);
  // The first warning of the episode is remembered.
  EXPECT_EQ(m.onTest(true, 3.0), DriftState::kWarn);
  EXPECT_DOUBLE_EQ(*m.firstWarnStamp(), 1.0);
  EXPECT_FALSE(m.firstErrorStamp());
  EXPECT_EQ(m.onTest(true, 4.0), DriftState::kError);
  // Confirmed: an inconclusive window does not clear it, only a new reference does.
  EXPECT_EQ(m.onTest(false, 5.0), DriftState::kError);
  EXPECT_EQ(m.onTest(true, 6.0), DriftState::kError);
  EXPECT_DOUBLE_EQ(*m.firstErrorStamp(), 4.0);
  m.reset();
  EXPECT_EQ(m.state(), DriftState::kOk);
  EXPECT_FALSE(m.firstWarnStamp());
  EXPECT_FALSE(m.firstErrorStamp());
}

TEST(DriftStateMachine, ConfirmWindowsCountsConsecutiveChanges) {
  DriftStateMachine three(3);
  three.onTest(true, 1.0);
  three.onTest(true, 2.0);
  EXPECT_EQ(three.state(), DriftState::kWarn);
  three.onTest(false, 3.0);
  three.onTest(true, 4.0);
  three.onTest(true, 5.0);
  EXPECT_EQ(three.state(), DriftState::kWarn);
  EXPECT_EQ(three.onTest(true, 6.0), DriftState::kError);
  DriftStateMachine one(1);
  EXPECT_EQ(one.onTest(true, 1.0), DriftState::kError);
  EXPECT_DOUBLE_EQ(*one.firstWarnStamp(), 1.0);
  EXPECT_THROW(DriftStateMachine(0), std::invalid_argument);
}

TEST(DriftStateMachine, StateNames) {
  EXPECT_STREQ(toString(DriftState::kOk), "OK");
  EXPECT_STREQ(toString(DriftState::kWarn), "WARN");
  EXPECT_STREQ(toString(DriftState::kError), "ERROR");
}

TEST(SignChangePoint, SplitsWhereTheSignsTurn) {
  // Old pairs fit the old pose better (negative), new ones the new pose (positive).
  EXPECT_EQ(signChangePoint({-1, -2, -1, -3, 2, 1, 3, 2, 1, 4}, 3), 4u);
  // A stray positive and a stray negative (mismatched pairs) do not move the split.
  EXPECT_EQ(signChangePoint({-1, 5, -1, -3, 2, 1, -3, 2, 1, 4}, 3), 4u);
  // Zeros (pairs neither pose explains) are neutral; ties keep the later split.
  EXPECT_EQ(signChangePoint({-1, -1, 0, 0, 1, 1, 1}, 2), 4u);
}

TEST(SignChangePoint, KeepsAtLeastMinAfterPairsAfterTheSplit) {
  EXPECT_EQ(signChangePoint({-1, -1, -1, -1, -1, 1}, 3), 3u);
  EXPECT_EQ(signChangePoint({1, 1, 1, 1}, 2), 0u);
  EXPECT_EQ(signChangePoint({1, 1}, 2), 0u);
  EXPECT_EQ(signChangePoint({}, 6), 0u);
}
