#pragma once
// One solid of a frame's snapshot of the world, already in the LiDAR frame.

#include "thermal_lidar_calibration/synthetic/body_model.hpp"

namespace thermal_lidar_calibration {
namespace synthetic {

struct WorldObject {
  Solid solid;            // LiDAR frame
  int person_id = 0;      // > 0 for a person (persistent id), 0 for clutter
  int clutter_id = 0;     // > 0 for clutter (posts, bushes)
  double grey_level = 0;  // apparent temperature on the mono8 scale (0..255)
  bool isPerson() const { return person_id > 0; }
};

}  // namespace synthetic
}  // namespace thermal_lidar_calibration
