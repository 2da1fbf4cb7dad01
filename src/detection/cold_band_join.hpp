#pragma once
// The join of a person cut in two by a cold band across the body, for the thermal segmenter.
// Internal to the detection library.

#include "thermal_regions.hpp"

#include <opencv2/core.hpp>

#include <functional>
#include <string>
#include <vector>

namespace thermal_lidar_calibration {
namespace detection {

// A whole region that failed the person tests, and the first test it failed.
struct FailedRegion {
  WarmRegion region;
  std::string reason;
};

// A person cut in two by a cold band across the body (a belt, a cable in front, a colder coat
// over warmer trousers): the upper part may pass as a short person, the lower one (legs, no
// neck) fails. A failed region whose top lies at most 0.15 of the joined height below the bottom
// of a region above it (a person, or another failure; never a part of a split region), sharing
// half the narrower one's columns, and whose top row band continues the upper one's bottom band
// (cold_band_join.cpp), is joined to it when the whole passes the person tests. Two people are
// never joined: the lower region must have failed on its own. The joined pixels are relabelled
// in `labels` to the upper region's label. failureOf: the first person test a region fails, ""
// for a person. A joined failed region leaves `failed`; the whole goes to (or stays in) `kept`.
void joinAcrossColdBands(cv::Mat& labels, const std::function<std::string(const WarmRegion&)>& failureOf,
                         std::vector<WarmRegion>* kept, std::vector<FailedRegion>* failed);

}  // namespace detection
}  // namespace thermal_lidar_calibration
