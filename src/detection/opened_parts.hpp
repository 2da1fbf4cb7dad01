#pragma once
// The parts of the kept people that the thermal segmenter's opening removed, given back.
// Internal to the detection library.
//
// The opening (thermal_open_radius_px) removes specks and 1-px bridges, but it also removes every
// part of a person narrower than its square: the bottom rows of a leg, a head's rounded top and,
// on a low-resolution camera, whole legs and arms one or two pixels wide. The LiDAR's points on
// those parts then lie outside the mask, and always on the same side of it (below the body for
// the legs), so the fit leans: on five FieldSAFE-like raw drives by -0.025 deg about camera x and
// -0.54 cm along camera y on average; on a drive whose detected masks ended a pixel above the
// ideal ones in 549 of 7,450 columns, the fit from the detected masks and the ideal clusters
// leaned -0.056 deg / -1.54 cm, against -0.002 deg / +0.07 cm without the opening. On an MS2-like
// drive (640x256) the legs of far people are 1-2 px wide: given back only their shaved edges
// (2 steps), the fit leaned +0.17 deg; given back the legs (10 steps), +0.05 deg.
//
// So once the regions are judged, each person grows back into the warm pixels (those of the
// threshold, before the opening) connected to it, `steps` times by 4-neighbours: a reconstruction
// by geodesic dilation (Vincent 1993) limited to a limb's length. It never enters a region the
// opening kept that is not this person (a warm object touching a person by a thin bridge gets at
// most the bridge), and a pixel comes back only when it is at least as warm as the person's
// coolest parts, the kCoolestQuantile of its own warm pixels (not of the closing's fill between
// the legs): a removed leg is as warm as the body above it, while the specks that sun-heated
// ground leaves just above the threshold around the feet stay out. A pixel two people reach in
// the same step goes to the lower id; a speck the opening removed comes back only where it
// touches a person.

#include "thermal_lidar_calibration/detection/thermal_person_segmenter.hpp"

#include <opencv2/core.hpp>

#include <vector>

namespace thermal_lidar_calibration {
namespace detection {

constexpr double kCoolestQuantile = 0.05;  // of a person's warm pixels: its floor

// `ids` (CV_8UC1, 0 = background, person i + 1 for (*people)[i]) grows into the non-zero pixels
// of `warm` (CV_8UC1, the size of `image`, which is CV_8UC1 or CV_16UC1) that are not in
// `regions` outside the people (CV_8UC1, the opened and closed mask the people were cut from;
// empty: no such limit) and not cooler than floors[i], the kCoolestQuantile of that person's warm
// pixels, `steps` rounds; each person's bbox and area_px grow with it.
void restoreOpenedParts(const cv::Mat& image, const cv::Mat& warm, const cv::Mat& regions, int steps,
                        const std::vector<double>& floors, cv::Mat* ids, std::vector<ThermalPerson>* people);

}  // namespace detection
}  // namespace thermal_lidar_calibration
