// BadFrameReporter: the one wording and throttle of bad frames for the node and calibrate_bag.

#include "thermal_lidar_calibration/app/runtime/bad_frame_reporter.hpp"

#include <gtest/gtest.h>

namespace tlc = thermal_lidar_calibration;

TEST(BadFrameReporter, OneLinePerKindAndPeriodInTheFramesOwnTime) {
  tlc::BadFrameReporter reporter(5.0);
  const std::string first = reporter.reportAtStamp(1600000000.0, " (/mask)", "mask is 80x64 but camera_info says 640x512");
  EXPECT_EQ(first, "bad frame at 1600000000.000 (/mask): mask is 80x64 but camera_info says 640x512 (1 bad so far)");
  // 40 more of the same kind (other sizes) within 4 s of bag time: held back.
  for (int i = 0; i < 40; ++i) {
    EXPECT_EQ(reporter.reportAtStamp(1600000000.1 + 0.1 * i, " (/mask)",
                                     "mask is " + std::to_string(81 + i) + "x64 but camera_info says 640x512"),
              "");
  }
  // Another kind is said at once.
  EXPECT_NE(reporter.reportAtStamp(1600000002.0, "", "/clusters: no label field"), "");
  const std::string later = reporter.reportAtStamp(1600000006.0, " (/mask)", "mask is 1x1 but camera_info says 640x512");
  EXPECT_NE(later.find("(43 bad so far) (and 40 more like it in the last 5 s)"), std::string::npos) << later;
  EXPECT_EQ(reporter.total(), 43u);
}
