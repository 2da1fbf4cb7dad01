#pragma once
// ~resume, then the same drive played again from its start: the frames the stored session passed
// over by the skip rule (the skip_frames frames after each kept one) are offered again, with the
// skip rule starting afresh, and kept now they would sit next to a stored pair: consecutive
// frames, nearly the same data counted twice (on the kill-and-resume test drive, 8 of the 29
// gaps between the resumed fit's pairs were one frame). A live frame nearer to a stored pair
// than the skip rule keeps pairs apart is passed over as those were.
//
// The spacing is in frames; the stored pairs' frame numbers and stamps give the frame period
// (the median of stamp difference over frame difference between stored pairs in frame order).
// Without frame numbers (dataset bags from before them) or with fewer than two stored pairs the
// period is unknown and nothing is passed over.

#include <cstdint>
#include <optional>
#include <vector>

namespace thermal_lidar_calibration {

struct StoredPairStamp {
  double stamp_s = 0.0;
  std::optional<std::uint64_t> frame_index;
};

class StoredPairSpacing {
 public:
  StoredPairSpacing(std::vector<StoredPairStamp> pairs, int skip_frames);
  // A live frame at stamp_s lies within skip_frames frames of a stored pair (its own stamp aside).
  bool tooClose(double stamp_s) const;
  std::optional<double> framePeriodS() const { return period_s_; }

 private:
  std::vector<double> stamps_;  // sorted
  std::optional<double> period_s_;
  double window_s_ = 0.0;
};

}  // namespace thermal_lidar_calibration
