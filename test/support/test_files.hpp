#pragma once
// Helpers shared by the tests that write and read files: a fresh temporary directory (removed
// when the test program ends), and the message of the std::invalid_argument a call throws.

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace thermal_lidar_calibration {
namespace test_support {

namespace detail {
// Directories made by tempDir(), removed at exit unless TLC_KEEP_TEST_DIR is set (then listed,
// for looking at what a failing test wrote).
struct TempDirRegistry {
  std::vector<std::string> dirs;
  ~TempDirRegistry() {
    const bool keep = std::getenv("TLC_KEEP_TEST_DIR") != nullptr;
    for (const auto& d : dirs) {
      if (keep) {
        std::printf("kept %s\n", d.c_str());
      } else {
        std::error_code ignored;
        std::filesystem::remove_all(d, ignored);
      }
    }
  }
};
inline TempDirRegistry& tempDirRegistry() {
  static TempDirRegistry registry;
  return registry;
}
}  // namespace detail

// A new directory <base>/<prefix>XXXXXX (mkdtemp), base = $TLC_TEST_TMP or /tmp. Throws if it
// cannot be made: a test that silently wrote into /tmp itself would leave files behind.
inline std::string tempDir(const std::string& prefix) {
  const char* env = std::getenv("TLC_TEST_TMP");
  const std::string base = env && *env ? env : "/tmp";
  std::error_code ignored;
  std::filesystem::create_directories(base, ignored);
  std::string pattern = base + "/" + prefix + "XXXXXX";
  const char* dir = mkdtemp(pattern.data());
  if (!dir) throw std::runtime_error("cannot make a temporary directory under " + base);
  detail::tempDirRegistry().dirs.push_back(dir);
  return dir;
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
