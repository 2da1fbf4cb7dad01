// calibrate_bag: offline calibration from a ROS 1 bag. Parse, construct, run.

#include "thermal_lidar_calibration/tools/calibrate_bag.hpp"

#include <cstdio>
#include <exception>

int main(int argc, char** argv) {
  namespace tlc = thermal_lidar_calibration::ros_io;
  try {
    const tlc::CalibrateBagOptions options = tlc::parseCalibrateBagOptions(argc, argv);
    if (options.help) {
      std::fputs(tlc::calibrateBagUsage().c_str(), stdout);
      return 0;
    }
    return tlc::runCalibrateBag(options);
  } catch (const tlc::UsageError& e) {
    std::fprintf(stderr, "calibrate_bag: error: %s (see calibrate_bag --help)\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "calibrate_bag: error: %s\n", e.what());
    return 1;
  } catch (...) {
    std::fprintf(stderr, "calibrate_bag: error: unexpected failure\n");
    return 1;
  }
}
