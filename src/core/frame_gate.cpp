#include "thermal_lidar_calibration/core/frame_gate.hpp"

#include <sstream>
#include <stdexcept>
#include <string>

namespace thermal_lidar_calibration {

namespace {

void requireAtLeast(const char* key, int value, int minimum) {
  if (value < minimum) {
    std::ostringstream os;
    os << key << " = " << value << " is out of range: must be >= " << minimum;
    throw std::invalid_argument(os.str());
  }
}

}  // namespace

void GateConfig::validate() const {
  requireAtLeast("max_people", max_people, 1);
  requireAtLeast("skip_frames", skip_frames, 0);
  requireAtLeast("min_points_per_cluster", min_points_per_cluster, 1);
}

const char* toString(GateDecision decision) {
  switch (decision) {
    case GateDecision::kKept: return "kept";
    case GateDecision::kSkipped: return "skipped";
    case GateDecision::kBadMessage: return "bad_message";
    case GateDecision::kSmallCluster: return "small_cluster";
    case GateDecision::kCountMismatch: return "count_mismatch";
    case GateDecision::kNoPeople: return "no_people";
    case GateDecision::kTooManyPeople: return "too_many_people";
  }
  return "unknown";
}

std::uint64_t RejectionCounts::considered() const {
  std::uint64_t total = 0;
  for (const std::uint64_t n : by_decision) total += n;
  return total;
}

std::string RejectionCounts::summary() const {
  const RejectionCounts& c = *this;
  std::ostringstream os;
  os << "kept " << c[GateDecision::kKept] << "; rejected: unequal "
     << c[GateDecision::kCountMismatch] << ", none " << c[GateDecision::kNoPeople]
     << ", >H_max " << c[GateDecision::kTooManyPeople] << ", skipped "
     << c[GateDecision::kSkipped] << ", small cluster " << c[GateDecision::kSmallCluster]
     << ", bad " << c[GateDecision::kBadMessage] << ", non-finite points dropped "
     << nonfinite_points_dropped;
  return os.str();
}

FrameGate::FrameGate(GateConfig config) : config_(config) { config_.validate(); }

bool FrameGate::consumeSkip() {
  if (skip_remaining_ <= 0) return false;
  --skip_remaining_;
  ++counts_[GateDecision::kSkipped];
  return true;
}

GateDecision FrameGate::decide(int mask_people, int cluster_people,
                               int smallest_cluster_points) {
  const GateDecision decision = classify(mask_people, cluster_people, smallest_cluster_points);
  ++counts_[decision];
  if (decision == GateDecision::kKept) skip_remaining_ = config_.skip_frames;
  return decision;
}

GateDecision FrameGate::classify(int mask_people, int cluster_people, int smallest_cluster_points) const {
  GateDecision decision = GateDecision::kKept;
  if (cluster_people > 0 && smallest_cluster_points < config_.min_points_per_cluster) {
    decision = GateDecision::kSmallCluster;
  } else if (mask_people != cluster_people) {
    decision = GateDecision::kCountMismatch;
  } else if (mask_people <= 0) {
    decision = GateDecision::kNoPeople;
  } else if (mask_people > config_.max_people) {
    decision = GateDecision::kTooManyPeople;
  }
  return decision;
}

void FrameGate::recordBadMessage() { ++counts_[GateDecision::kBadMessage]; }

void FrameGate::reset() {
  skip_remaining_ = 0;
  counts_ = RejectionCounts{};
}

}  // namespace thermal_lidar_calibration
