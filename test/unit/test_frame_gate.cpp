// The gating sequence of Section 3.1: equal counts between 1 and H_max are kept, the next
// skip_frames candidates after a kept frame are not considered, every rejection is counted.

#include "thermal_lidar_calibration/core/frame_gate.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace tlc = thermal_lidar_calibration;
using tlc::GateDecision;

namespace {

constexpr int kNoClusters = std::numeric_limits<int>::max();

tlc::GateConfig config(int max_people = 3, int skip_frames = 3, int min_points = 3) {
  tlc::GateConfig c;
  c.max_people = max_people;
  c.skip_frames = skip_frames;
  c.min_points_per_cluster = min_points;
  return c;
}

// One candidate as the ingest path handles it: skip rule first, then the decision.
GateDecision offer(tlc::FrameGate& gate, int mask_people, int cluster_people,
                   int smallest = 100) {
  if (gate.consumeSkip()) return GateDecision::kSkipped;
  return gate.decide(mask_people, cluster_people, smallest);
}

}  // namespace

TEST(GateConfig, DefaultsAreThePapers) {
  const tlc::GateConfig c;
  EXPECT_EQ(c.max_people, 3);
  EXPECT_EQ(c.skip_frames, 3);
  EXPECT_NO_THROW(c.validate());
}

TEST(GateConfig, ValidateNamesKeyValueAndRange) {
  auto message = [](const tlc::GateConfig& c) {
    try {
      c.validate();
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string max_people = message(config(0, 3, 3));
  EXPECT_NE(max_people.find("max_people"), std::string::npos) << max_people;
  EXPECT_NE(max_people.find("0"), std::string::npos) << max_people;
  EXPECT_NE(max_people.find(">= 1"), std::string::npos) << max_people;

  const std::string skip = message(config(3, -1, 3));
  EXPECT_NE(skip.find("skip_frames"), std::string::npos) << skip;
  EXPECT_NE(skip.find("-1"), std::string::npos) << skip;
  EXPECT_NE(skip.find(">= 0"), std::string::npos) << skip;

  const std::string min_points = message(config(3, 3, 0));
  EXPECT_NE(min_points.find("min_points_per_cluster"), std::string::npos) << min_points;

  EXPECT_NO_THROW(config(1, 0, 1).validate());
  EXPECT_THROW(tlc::FrameGate(config(0, 3, 3)), std::invalid_argument);
}

TEST(GateDecision, ToString) {
  EXPECT_STREQ(tlc::toString(GateDecision::kKept), "kept");
  EXPECT_STREQ(tlc::toString(GateDecision::kSkipped), "skipped");
  EXPECT_STREQ(tlc::toString(GateDecision::kBadMessage), "bad_message");
  EXPECT_STREQ(tlc::toString(GateDecision::kSmallCluster), "small_cluster");
  EXPECT_STREQ(tlc::toString(GateDecision::kCountMismatch), "count_mismatch");
  EXPECT_STREQ(tlc::toString(GateDecision::kNoPeople), "no_people");
  EXPECT_STREQ(tlc::toString(GateDecision::kTooManyPeople), "too_many_people");
}

TEST(FrameGate, EqualCountsAreKeptUnequalAreNot) {
  tlc::FrameGate gate(config(3, 0, 3));
  EXPECT_EQ(offer(gate, 1, 1), GateDecision::kKept);
  EXPECT_EQ(offer(gate, 2, 2), GateDecision::kKept);
  EXPECT_EQ(offer(gate, 1, 2), GateDecision::kCountMismatch);
  EXPECT_EQ(offer(gate, 2, 1), GateDecision::kCountMismatch);
  EXPECT_EQ(offer(gate, 0, 1), GateDecision::kCountMismatch);
  EXPECT_EQ(offer(gate, 1, 0, kNoClusters), GateDecision::kCountMismatch);
}

TEST(FrameGate, NobodyInEitherIsNoPeople) {
  tlc::FrameGate gate(config());
  EXPECT_EQ(offer(gate, 0, 0, kNoClusters), GateDecision::kNoPeople);
  // Not kept, so no skip is armed.
  EXPECT_EQ(offer(gate, 1, 1), GateDecision::kKept);
}

TEST(FrameGate, MaxPeopleBoundary) {
  tlc::FrameGate gate(config(3, 0, 3));
  EXPECT_EQ(offer(gate, 3, 3), GateDecision::kKept);
  EXPECT_EQ(offer(gate, 4, 4), GateDecision::kTooManyPeople);
  // Unequal beyond H_max is a mismatch first.
  EXPECT_EQ(offer(gate, 4, 5), GateDecision::kCountMismatch);

  tlc::FrameGate one(config(1, 0, 3));
  EXPECT_EQ(offer(one, 1, 1), GateDecision::kKept);
  EXPECT_EQ(offer(one, 2, 2), GateDecision::kTooManyPeople);
}

TEST(FrameGate, SmallClusterComesFirst) {
  tlc::FrameGate gate(config(3, 0, 5));
  EXPECT_EQ(offer(gate, 1, 1, 4), GateDecision::kSmallCluster);
  EXPECT_EQ(offer(gate, 1, 2, 4), GateDecision::kSmallCluster);   // before count_mismatch
  EXPECT_EQ(offer(gate, 4, 4, 4), GateDecision::kSmallCluster);   // before too_many_people
  EXPECT_EQ(offer(gate, 1, 1, 5), GateDecision::kKept);           // exactly the minimum is fine
  EXPECT_EQ(offer(gate, 0, 0, kNoClusters), GateDecision::kNoPeople);
}

TEST(FrameGate, SkipRuleKeptThenThreeSkippedThenConsideredAgain) {
  tlc::FrameGate gate(config(3, 3, 3));
  std::vector<GateDecision> got;
  got.push_back(offer(gate, 1, 1));  // kept
  got.push_back(offer(gate, 1, 1));  // skipped although it would be kept
  got.push_back(offer(gate, 2, 1));  // skipped although it would be a mismatch
  got.push_back(offer(gate, 0, 0));  // skipped
  got.push_back(offer(gate, 1, 2));  // considered again: mismatch (does not arm a skip)
  got.push_back(offer(gate, 2, 2));  // kept
  got.push_back(offer(gate, 2, 2));  // skipped
  got.push_back(offer(gate, 2, 2));  // skipped
  got.push_back(offer(gate, 2, 2));  // skipped
  got.push_back(offer(gate, 2, 2));  // kept
  const std::vector<GateDecision> want = {
      GateDecision::kKept,    GateDecision::kSkipped,       GateDecision::kSkipped,
      GateDecision::kSkipped, GateDecision::kCountMismatch, GateDecision::kKept,
      GateDecision::kSkipped, GateDecision::kSkipped,       GateDecision::kSkipped,
      GateDecision::kKept};
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < want.size(); ++i) {
    EXPECT_EQ(got[i], want[i]) << "candidate " << i << ": got " << tlc::toString(got[i])
                               << ", want " << tlc::toString(want[i]);
  }
  EXPECT_EQ(gate.counts()[GateDecision::kKept], 3u);
  EXPECT_EQ(gate.counts()[GateDecision::kSkipped], 6u);
  EXPECT_EQ(gate.counts()[GateDecision::kCountMismatch], 1u);
  EXPECT_EQ(gate.counts().considered(), 10u);
}

TEST(FrameGate, RejectedFramesDoNotArmTheSkip) {
  tlc::FrameGate gate(config(3, 3, 3));
  EXPECT_EQ(offer(gate, 1, 2), GateDecision::kCountMismatch);
  EXPECT_EQ(offer(gate, 0, 0), GateDecision::kNoPeople);
  EXPECT_EQ(offer(gate, 5, 5), GateDecision::kTooManyPeople);
  EXPECT_EQ(offer(gate, 1, 1, 1), GateDecision::kSmallCluster);
  gate.recordBadMessage();
  EXPECT_EQ(offer(gate, 1, 1), GateDecision::kKept);
}

TEST(FrameGate, SkipFramesZeroConsidersEveryFrame) {
  tlc::FrameGate gate(config(3, 0, 3));
  for (int i = 0; i < 5; ++i) {
    EXPECT_FALSE(gate.consumeSkip());
    EXPECT_EQ(gate.decide(1, 1, 10), GateDecision::kKept);
  }
  EXPECT_EQ(gate.counts()[GateDecision::kKept], 5u);
  EXPECT_EQ(gate.counts()[GateDecision::kSkipped], 0u);
}

TEST(FrameGate, CountsByReasonAndSummary) {
  tlc::FrameGate gate(config(3, 3, 3));
  // 2 kept (with 3 skipped after the first, 2 after the second at the end), mismatches, etc.
  offer(gate, 1, 1);                // kept
  for (int i = 0; i < 3; ++i) offer(gate, 1, 1);  // 3 skipped
  offer(gate, 1, 2);                // unequal
  offer(gate, 2, 0, kNoClusters);   // unequal
  offer(gate, 0, 0, kNoClusters);   // none
  offer(gate, 0, 0, kNoClusters);   // none
  offer(gate, 0, 0, kNoClusters);   // none
  offer(gate, 4, 4);                // >H_max
  offer(gate, 1, 1, 2);             // small cluster
  gate.recordBadMessage();          // bad
  offer(gate, 2, 2);                // kept
  offer(gate, 2, 2);                // skipped
  offer(gate, 2, 2);                // skipped
  gate.counts().nonfinite_points_dropped += 7;

  const tlc::RejectionCounts& c = gate.counts();
  EXPECT_EQ(c[GateDecision::kKept], 2u);
  EXPECT_EQ(c[GateDecision::kSkipped], 5u);
  EXPECT_EQ(c[GateDecision::kCountMismatch], 2u);
  EXPECT_EQ(c[GateDecision::kNoPeople], 3u);
  EXPECT_EQ(c[GateDecision::kTooManyPeople], 1u);
  EXPECT_EQ(c[GateDecision::kSmallCluster], 1u);
  EXPECT_EQ(c[GateDecision::kBadMessage], 1u);
  EXPECT_EQ(c.considered(), 15u);
  EXPECT_EQ(c.summary(),
            "kept 2; rejected: unequal 2, none 3, >H_max 1, skipped 5, small cluster 1, bad 1, "
            "non-finite points dropped 7");
}

TEST(FrameGate, ResetClearsCountsAndPendingSkip) {
  tlc::FrameGate gate(config(3, 3, 3));
  EXPECT_EQ(offer(gate, 1, 1), GateDecision::kKept);
  gate.reset();
  EXPECT_EQ(gate.counts().considered(), 0u);
  EXPECT_EQ(offer(gate, 1, 1), GateDecision::kKept);  // no skip left over
}

TEST(RejectionCounts, EmptySummary) {
  const tlc::RejectionCounts c;
  EXPECT_EQ(c.considered(), 0u);
  EXPECT_EQ(c.summary(),
            "kept 0; rejected: unequal 0, none 0, >H_max 0, skipped 0, small cluster 0, bad 0, "
            "non-finite points dropped 0");
}
