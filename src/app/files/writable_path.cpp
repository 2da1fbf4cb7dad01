#include "thermal_lidar_calibration/app/files/writable_path.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace thermal_lidar_calibration {
namespace {

std::string directoryOf(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  if (slash == std::string::npos) return ".";
  return slash == 0 ? "/" : path.substr(0, slash);
}

}  // namespace

std::string whyNotWritable(const std::string& path) {
  if (path.empty()) return "the path is empty";
  if (path.back() == '/') return path + " names a directory; add a file name";
  const std::string dir = directoryOf(path);
  struct stat st {};
  if (::stat(dir.c_str(), &st) != 0) {
    return "directory " + dir + " of " + path + " does not exist (" + std::strerror(errno) +
           "); create it or choose another path";
  }
  if (!S_ISDIR(st.st_mode)) return dir + " (in " + path + ") is not a directory";
  if (::stat(path.c_str(), &st) == 0) {
    if (S_ISDIR(st.st_mode)) return path + " is a directory; add a file name";
    // Open without truncating: the check must not destroy an existing result.
    const int fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
    if (fd < 0) return "cannot write " + path + " (" + std::strerror(errno) + ")";
    ::close(fd);
  }
  // Results and bags are written next to the target and renamed, so the directory itself must
  // take a new file.
  const std::string probe = dir + "/.tlc_write_probe_" + std::to_string(::getpid());
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0) {
    return "cannot create files in " + dir + " (for " + path + ": " + std::strerror(errno) +
           "); choose a writable directory";
  }
  ::close(fd);
  ::unlink(probe.c_str());
  return "";
}

}  // namespace thermal_lidar_calibration
