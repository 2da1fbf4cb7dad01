#pragma once
// Helpers shared by the tests that write and read files: a fresh temporary directory, and the
// message of the std::invalid_argument a call throws.

#include <cstdlib>
#include <functional>
#include <stdexcept>
#include <string>

namespace thermal_lidar_calibration {
namespace test_support {

// A new directory /tmp/<prefix>XXXXXX (mkdtemp); /tmp itself if it cannot be made.
inline std::string tempDir(const std::string& prefix) {
  std::string pattern = "/tmp/" + prefix + "XXXXXX";
  const char* dir = mkdtemp(pattern.data());
  return dir ? dir : "/tmp";
}

// What `f` throws as std::invalid_argument, or "<no exception>" if it returns normally.
inline std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "<no exception>";
}

}  // namespace test_support
}  // namespace thermal_lidar_calibration
