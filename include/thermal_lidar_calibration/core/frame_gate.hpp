#pragma once
// Section 3.1 of the paper: keep a frame only when both modalities count the same number of
// people, between 1 and H_max; after a kept frame the next `skip_frames` candidates are not
// considered. Every rejection is counted by reason.

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>

namespace thermal_lidar_calibration {

struct GateConfig {
  int max_people = 3;              // H_max (Table 1 / Section 4), >= 1
  int skip_frames = 3;             // candidates ignored after a kept frame, >= 0
  int min_points_per_cluster = 3;  // a person cluster with fewer points rejects the frame, >= 1
  void validate() const;           // throws std::invalid_argument naming the key and range
};

enum class GateDecision : std::uint8_t {
  kKept = 0,
  kSkipped,          // one of the skip_frames candidates after a kept frame
  kBadMessage,       // could not decode (encoding, missing label field, size mismatch, ...)
  kSmallCluster,     // a cluster below min_points_per_cluster
  kCountMismatch,    // mask and clusters disagree on the number of people
  kNoPeople,         // both see nobody
  kTooManyPeople,    // agree, but more than max_people
};
constexpr std::size_t kGateDecisionCount = 7;
const char* toString(GateDecision decision);  // "kept", "skipped", "bad_message", ...

struct RejectionCounts {
  std::array<std::uint64_t, kGateDecisionCount> by_decision{};  // index = GateDecision
  std::uint64_t nonfinite_points_dropped = 0;

  std::uint64_t& operator[](GateDecision d) { return by_decision[static_cast<std::size_t>(d)]; }
  std::uint64_t operator[](GateDecision d) const {
    return by_decision[static_cast<std::size_t>(d)];
  }
  std::uint64_t considered() const;  // all candidate frames offered
  // "kept 12; rejected: unequal 40, none 85, >H_max 3, skipped 36, small cluster 2, bad 1"
  std::string summary() const;
};

// Pure decision logic (no images): the skip rule and the count rule.
class FrameGate {
 public:
  explicit FrameGate(GateConfig config);

  // Call once per synchronized candidate frame, before decoding it. True means "skip this one"
  // (already counted as kSkipped).
  bool consumeSkip();
  // Decide on a decoded frame from the two people counts and the smallest cluster size
  // (pass a large value when there are no clusters). Counts the decision; kKept arms the skip.
  GateDecision decide(int mask_people, int cluster_people, int smallest_cluster_points);
  // What decide() would say, without counting it or arming the skip.
  GateDecision classify(int mask_people, int cluster_people, int smallest_cluster_points) const;
  // A candidate that could not be decoded.
  void recordBadMessage();

  const RejectionCounts& counts() const { return counts_; }
  RejectionCounts& counts() { return counts_; }
  const GateConfig& config() const { return config_; }
  void reset();  // clears counts and the pending skip

 private:
  GateConfig config_;
  int skip_remaining_ = 0;
  RejectionCounts counts_;
};

}  // namespace thermal_lidar_calibration
