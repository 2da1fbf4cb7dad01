#pragma once
// Checks at start that a file the program will write later can be written: a node that accepts
// an unwritable ~output_file or ~dataset_bag fails only once pairs are kept, an hour into a drive.

#include <string>

namespace thermal_lidar_calibration {

// "" when `path` can be written (its directory exists and takes a new file, and the file, if it
// exists, is a regular file open for writing); else why not, naming the path or its directory
// and what to do. The directory check creates and removes a probe file, so it holds for root,
// read-only mounts and full inode tables alike. Relative paths are relative to the current
// directory (for a node started by roslaunch, ROS_HOME).
std::string whyNotWritable(const std::string& path);

}  // namespace thermal_lidar_calibration
