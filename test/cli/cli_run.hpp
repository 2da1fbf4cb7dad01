#pragma once
// Running a command-line tool from a CLI test: its exit code, stdout and stderr, and the
// bad-input contract every tool keeps (exit 1 or 2, no crash, exactly one error line, the last).

#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

// The CLI test targets get the built tools' paths from CMake (test/CMakeLists.txt).
#if !defined(CALIBRATE_BAG_EXE) || !defined(MAKE_SYNTHETIC_BAG_EXE)
#error "CALIBRATE_BAG_EXE and MAKE_SYNTHETIC_BAG_EXE must name the calibrate_bag and make_synthetic_bag binaries"
#endif

namespace tlc_cli_test {

struct RunResult {
  int exit_code = -1;
  bool signalled = false;
  std::string out, err;
};

inline std::string readFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Runs `exe args` through the shell, its output captured in files under `dir`.
inline RunResult runTool(const std::string& exe, const std::string& args, const std::string& dir) {
  const std::string out = dir + "/stdout.txt", err = dir + "/stderr.txt";
  const std::string cmd = "'" + exe + "' " + args + " >'" + out + "' 2>'" + err + "'";
  const int status = std::system(cmd.c_str());
  RunResult r;
  if (WIFEXITED(status)) {
    r.exit_code = WEXITSTATUS(status);
    r.signalled = r.exit_code >= 128;  // the shell reports a signal as 128 + n
  } else {
    r.signalled = true;
  }
  r.out = readFile(out);
  r.err = readFile(err);
  return r;
}

// The bad-input contract: exit `code`, no crash, exactly one line starting with `prefix` (e.g.
// "calibrate_bag: error: "), and it is the last. Returns that line.
inline std::string expectOneLineError(const RunResult& r, const std::string& prefix, int code = 1) {
  EXPECT_FALSE(r.signalled) << r.err;
  EXPECT_EQ(r.exit_code, code) << r.err;
  std::istringstream lines(r.err);
  std::string line, error_line, last;
  int errors = 0;
  while (std::getline(lines, line)) {
    if (line.rfind(prefix, 0) == 0) {
      ++errors;
      error_line = line;
    }
    if (!line.empty()) last = line;
  }
  EXPECT_EQ(errors, 1) << r.err;
  EXPECT_EQ(last, error_line) << r.err;
  return error_line;
}

}  // namespace tlc_cli_test
