#pragma once
// Internal: the thread count a parallel loop uses; 0 (or less) means every core.

#include <algorithm>
#include <thread>

namespace thermal_lidar_calibration {

inline int resolveThreads(int threads) {
  return threads > 0 ? threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

}  // namespace thermal_lidar_calibration
