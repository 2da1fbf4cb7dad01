// detect_people: the person detectors on single files (see detection_tool/detect_people.hpp).
#include "thermal_lidar_calibration/detection_tool/detect_people.hpp"

#include <iostream>

int main(int argc, char** argv) {
  return thermal_lidar_calibration::detection_tool::detectPeopleMain(argc, argv, std::cout, std::cerr);
}
