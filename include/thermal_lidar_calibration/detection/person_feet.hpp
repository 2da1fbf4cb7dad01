#pragma once
// A person's lowest points, given back after ground removal.
//
// Objects are clustered from the points more than lidar_ground_tolerance_m above the local
// ground, so every person loses its feet and ankles (0.15 m by default), the points nearest the
// bottom of its mask. Given back, they moved the raw synthetic fits (calibrate_bag --detect,
// seeds 1-5) by a little and the right way: the mean along camera y on clean FieldSAFE-like
// drives -0.54 -> -0.30 cm, on clean MS2-like drives +1.37 -> +0.83 cm (about camera x +0.054 ->
// +0.033 deg); the realistic drives' means moved by at most 0.06 cm and 0.007 deg
// (docs/validation/accuracy.md). Most of the raw fits' vertical lean was the thermal mask's
// (detection/thermal_person_segmenter.hpp, thermal_restore_edges_px).
//
// A point of the ground band (min_height_m < height <= max_height_m) belongs to a person when it
// stands under the person's legs: horizontally within the legs' footprint (their distance from
// the legs' axis, plus kFootMarginM) and no nearer to the sensor than the legs' front (less
// kFootMarginM). The ground in front of a person is nearer than its legs, the ground behind it is
// hidden by them; a band point under two people goes to the nearer axis. min_height_m keeps the
// ground itself out where the ground estimate is off by a few centimetres.

#include <Eigen/Core>
#include <vector>

namespace thermal_lidar_calibration {
namespace detection {

// The legs: a person's points up to this height above the ground give the footprint.
constexpr float kLegsTopM = 0.6f;
constexpr float kFootMarginM = 0.05f;

// For each person (indices into `levelled` / `heights`, the levelled frame of TerrainGround),
// the indices of the band points under it, ascending. A person without points below kLegsTopM
// (legs hidden) gets none.
std::vector<std::vector<int>> feetUnder(const std::vector<Eigen::Vector3f>& levelled,
                                        const std::vector<float>& heights,
                                        const std::vector<std::vector<int>>& people, float min_height_m,
                                        float max_height_m);

}  // namespace detection
}  // namespace thermal_lidar_calibration
