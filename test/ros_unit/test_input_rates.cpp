// InputRates: rates over a window, and naming a topic that stops or never starts (issue 8).

#include "thermal_lidar_calibration/node/input_rates.hpp"

#include <gtest/gtest.h>

namespace tlc = thermal_lidar_calibration;
using Clock = tlc::InputRates::Clock;
using std::chrono::milliseconds;

TEST(InputRates, RatesOverTheWindow) {
  const Clock::time_point t0 = Clock::now();
  tlc::InputRates rates({"/image", "/mask"}, t0, 5.0, 5.0);
  for (int i = 0; i < 100; ++i) rates.message(0, t0 + milliseconds(100 * i));  // 10 Hz for 10 s
  EXPECT_NEAR(rates.rateHz(0, t0 + milliseconds(9950)), 10.0, 0.3);
  EXPECT_EQ(rates.rateHz(1, t0 + milliseconds(9950)), 0.0);
  EXPECT_EQ(rates.total(0), 100u);
}

TEST(InputRates, NamesATopicThatNeverStarts) {
  const Clock::time_point t0 = Clock::now();
  tlc::InputRates rates({"/image", "/mask", "/clusters"}, t0, 5.0, 5.0);
  for (int i = 0; i < 120; ++i) {
    rates.message(0, t0 + milliseconds(100 * i));
    rates.message(2, t0 + milliseconds(100 * i + 5));
  }
  EXPECT_EQ(rates.problem(t0 + milliseconds(3000)), "") << "within the start grace";
  const std::string p = rates.problem(t0 + milliseconds(12000));
  EXPECT_NE(p.find("no message ever on /mask (12 s since start)"), std::string::npos) << p;
  EXPECT_NE(p.find("while /image, /clusters arrive"), std::string::npos) << p;
}

TEST(InputRates, NamesATopicThatStopsAndForgetsItWhenItComesBack) {
  const Clock::time_point t0 = Clock::now();
  tlc::InputRates rates({"/image", "/mask"}, t0, 5.0, 5.0);
  for (int i = 0; i < 200; ++i) {
    rates.message(0, t0 + milliseconds(100 * i));
    if (i < 50) rates.message(1, t0 + milliseconds(100 * i));
  }
  const std::string p = rates.problem(t0 + milliseconds(19950));
  EXPECT_NE(p.find("no messages on /mask for 15 s while /image arrive"), std::string::npos) << p;
  rates.message(1, t0 + milliseconds(20000));
  EXPECT_EQ(rates.problem(t0 + milliseconds(20050)), "");
  // Everything silent: the message says so.
  EXPECT_NE(rates.problem(t0 + milliseconds(40000)).find("is the bag or the sensors running"), std::string::npos);
}
