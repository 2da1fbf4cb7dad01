#pragma once
// Internal: max/min with the exact semantics of the SSE/AVX max and min instructions (the second
// operand when either is NaN). The loss kernels' scalar code and DistanceMap's reference rules
// use these so that a NaN projection clamps into the box exactly as the vector code does.

namespace thermal_lidar_calibration {

inline float maxps(float a, float b) { return a > b ? a : b; }
inline float minps(float a, float b) { return a < b ? a : b; }
inline float clampps(float x, float lo, float hi) { return minps(maxps(x, lo), hi); }

}  // namespace thermal_lidar_calibration
