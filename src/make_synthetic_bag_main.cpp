// make_synthetic_bag: a synthetic thermal camera + LiDAR drive among people into a ROS 1 bag,
// and the true extrinsic into a YAML file. Parse, construct, run.
// Bad arguments or settings: one-line error on stderr, exit 2. Other failures: exit 1.

#include "thermal_lidar_calibration/tools/make_synthetic_bag.hpp"

#include <cstdio>
#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

int main(int argc, char** argv) {
  namespace tlc = thermal_lidar_calibration::ros_io;
  try {
    const tlc::MakeSyntheticBagOptions options =
        tlc::parseMakeSyntheticBagOptions(std::vector<std::string>(argv + 1, argv + argc));
    if (options.help) {
      std::fputs(tlc::makeSyntheticBagUsage().c_str(), stdout);
      return 0;
    }
    return tlc::runMakeSyntheticBag(options);
  } catch (const std::invalid_argument& e) {  // UsageError, or settings the rig refuses
    std::fprintf(stderr, "make_synthetic_bag: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_synthetic_bag: %s\n", e.what());
    return 1;
  }
}
