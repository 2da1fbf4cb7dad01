// The feet given back after ground removal (detection/person_feet.hpp): on crafted HDL-32E and
// VLP-16 scans, a person's lowest returns join its cluster and the ground around it does not.

#include "thermal_lidar_calibration/detection/lidar_person_detector.hpp"
#include "thermal_lidar_calibration/detection/person_feet.hpp"

#include "../support/lidar_scene.hpp"

#include <gtest/gtest.h>

#include <algorithm>

namespace thermal_lidar_calibration {
namespace {

using detection::LidarDetection;
using detection::LidarDetectorConfig;
using detection::LidarPersonDetector;
using synthetic::LidarModel;
using test_support::castScan;
using test_support::CraftedScan;
using test_support::Mount;
using test_support::personAt;
using test_support::Terrain;

struct FeetCount {
  int person_low = 0;     // the person's returns in the ground band, above the feet's floor
  int person_low_in = 0;  // those in its cluster
  int lowest_in_mm = 0;   // lowest height above the ground in the cluster, mm
  int foreign = 0;        // returns of anything else in the cluster
};

FeetCount countFeet(const CraftedScan& scan, const LidarDetectorConfig& config) {
  LidarPersonDetector detector(config);
  const LidarDetection d = detector.detect(scan.points);
  EXPECT_EQ(d.people.size(), 1u);
  const std::vector<float>& h = detector.ground().heights();
  std::vector<char> in(scan.points.size(), 0);
  for (const int i : d.indices) in[static_cast<std::size_t>(i)] = 1;
  FeetCount c;
  float lowest = 10.f;
  for (std::size_t i = 0; i < scan.points.size(); ++i) {
    if (in[i]) {
      lowest = std::min(lowest, h[i]);
      c.foreign += scan.person_id[i] != 1;
    }
    if (scan.person_id[i] == 1 && h[i] > config.person.feet_min_height_m &&
        h[i] <= config.ground.tolerance_m) {
      ++c.person_low;
      c.person_low_in += in[i];
    }
  }
  c.lowest_in_mm = static_cast<int>(lowest * 1000.f);
  return c;
}

TEST(PersonFeet, ThePersonsLowestReturnsJoinItsClusterAndTheGroundDoesNot) {
  const Terrain flat = Terrain::flat();
  int with_feet = 0;  // ranges where some beam meets the feet (the rings are sparse down there)
  for (double range = 4.0; range <= 16.0; range += 1.0) {
    const CraftedScan scan = castScan(LidarModel::hdl32e(), flat, Mount{}, {personAt(flat, range, 0.5, 1)});
    const FeetCount c = countFeet(scan, LidarDetectorConfig{});
    EXPECT_EQ(c.foreign, 0) << range << " m";
    if (c.person_low == 0) continue;
    ++with_feet;
    EXPECT_EQ(c.person_low_in, c.person_low) << range << " m";
    EXPECT_LT(c.lowest_in_mm, 150) << range << " m: below the ground tolerance";
  }
  EXPECT_GE(with_feet, 4);
}

TEST(PersonFeet, TurnedOffAtTheGroundToleranceTheClusterStartsAboveIt) {
  const Terrain flat = Terrain::flat();
  const CraftedScan scan = castScan(LidarModel::hdl32e(), flat, Mount{}, {personAt(flat, 6.0, 0.5, 1)});
  LidarDetectorConfig off;
  off.person.feet_min_height_m = off.ground.tolerance_m;
  const FeetCount c = countFeet(scan, off);
  EXPECT_GT(c.lowest_in_mm, 150);
  EXPECT_EQ(c.person_low, 0);
}

TEST(PersonFeet, RangeNoiseRollingGroundAndATiltedMountAddNoGround) {
  const Terrain rolling = Terrain::rolling(0.3);
  Mount tilted;
  tilted.pitch_deg = 4.0;
  tilted.roll_deg = -2.0;
  for (const LidarModel& lidar : {LidarModel::hdl32e(), LidarModel::vlp16()}) {
    for (std::uint64_t seed : {1, 2, 3}) {
      const CraftedScan scan = castScan(lidar, rolling, tilted, {personAt(rolling, 7.0 + seed, 1.0, 1)}, 0.02, seed);
      const FeetCount c = countFeet(scan, LidarDetectorConfig{});
      EXPECT_EQ(c.foreign, 0) << "seed " << seed;
      EXPECT_GE(c.person_low_in, c.person_low / 2) << "seed " << seed;
    }
  }
}

TEST(PersonFeet, ABandPointUnderTwoPeopleGoesToTheNearerAxisAndLegslessPeopleGetNone) {
  using Eigen::Vector3f;
  // Legs (0.3 m up) of person A about the axis (5, 0) and of B about (5, 0.12): footprints of
  // radius 0.05 + kFootMarginM that overlap; person C shows only a torso.
  std::vector<Vector3f> levelled = {{5.0f, -0.05f, 0.3f}, {5.0f, 0.05f, 0.3f}, {5.0f, 0.07f, 0.3f},
                                    {5.0f, 0.17f, 0.3f},  {9.0f, 0.0f, 1.2f}};
  std::vector<float> heights = {0.3f, 0.3f, 0.3f, 0.3f, 1.2f};
  const auto band = [&](float x, float y, float h) {
    levelled.emplace_back(x, y, h);
    heights.push_back(h);
    return static_cast<int>(heights.size()) - 1;
  };
  const int nearer_b = band(5.02f, 0.07f, 0.1f);   // 0.054 from B's axis, 0.073 from A's
  const int nearer_a = band(5.02f, 0.04f, 0.1f);   // 0.045 from A's, 0.081 from B's
  band(4.8f, 0.0f, 0.1f);                          // in front of both legs: ground
  band(5.0f, 0.0f, 0.01f);                         // below the floor
  band(5.0f, 0.3f, 0.1f);                          // beside B, outside its footprint
  band(9.0f, 0.0f, 0.1f);                          // under C, who shows no legs
  const std::vector<std::vector<int>> people = {{0, 1}, {2, 3}, {4}};
  const auto feet = detection::feetUnder(levelled, heights, people, 0.03f, 0.15f);
  ASSERT_EQ(feet.size(), 3u);
  EXPECT_EQ(feet[0], (std::vector<int>{nearer_a}));
  EXPECT_EQ(feet[1], (std::vector<int>{nearer_b}));
  EXPECT_TRUE(feet[2].empty());
  EXPECT_TRUE(detection::feetUnder(levelled, heights, people, 0.15f, 0.15f)[0].empty()) << "empty band";
}

}  // namespace
}  // namespace thermal_lidar_calibration
