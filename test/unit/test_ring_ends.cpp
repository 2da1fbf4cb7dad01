// The two points where each LiDAR ring leaves a person, measured against the person's own region,
// and the loss's term for them (issue 24): with masks eroded or dilated at random, as a
// segmentation does, a mask loss alone shrinks the projected people (the translation leans
// forward); charged their distance along the row from where they should lie, the ends pull it back.
#include "thermal_lidar_calibration/core/calibrator.hpp"
#include "thermal_lidar_calibration/core/loss.hpp"
#include "thermal_lidar_calibration/core/local_refinement.hpp"
#include "thermal_lidar_calibration/core/person_timing.hpp"
#include "thermal_lidar_calibration/core/pose_difference.hpp"
#include "thermal_lidar_calibration/core/random.hpp"
#include "thermal_lidar_calibration/core/ring_ends.hpp"

#include "../support/synthetic_pairs.hpp"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <numeric>
#include <set>

using namespace thermal_lidar_calibration;

namespace {

constexpr double kDeg = M_PI / 180.0;

Eigen::Vector3f polar(double range, double elevation_deg, double azimuth_deg) {
  const double e = elevation_deg * kDeg, a = azimuth_deg * kDeg;
  return Eigen::Vector3f(static_cast<float>(range * std::cos(e) * std::cos(a)),
                         static_cast<float>(range * std::cos(e) * std::sin(a)),
                         static_cast<float>(range * std::sin(e)));
}

// LiDAR x forward, y left, z up; camera x right, y down, z forward; the camera at the LiDAR.
Extrinsic lidarToCamera() {
  Eigen::Matrix3d R;
  R << 0, -1, 0, 0, 0, -1, 1, 0, 0;
  return Extrinsic::fromRotationMatrix(R, Eigen::Vector3d::Zero());
}

// People as flat boards facing the sensor, cut by rings every 1.33 deg at 0.16 deg azimuth steps
// (an HDL-32E's); each person's mask is the pixels whose centre the board covers, then eroded or
// dilated by a whole number of pixels in [-edge_px, edge_px].
std::vector<CalibrationPair> boardPairs(const CameraModel& camera, std::uint64_t seed, int edge_px) {
  Rng rng(seed);
  const Extrinsic to_camera = lidarToCamera();
  std::vector<CalibrationPair> pairs;
  for (int i = 0; i < 40; ++i) {
    CalibrationPair pair;
    pair.mask = cv::Mat::zeros(camera.height, camera.width, CV_8UC1);
    const int people = 1 + static_cast<int>(rng.index(3));
    for (int k = 1; k <= people; ++k) {
      const double range = rng.uniform(4.0, 12.0), width = rng.uniform(0.45, 0.6), height = rng.uniform(1.6, 1.9);
      const double centre_deg = rng.uniform(-18.0, 18.0);
      const double half_deg = std::atan2(0.5 * width, range) / kDeg;
      const double feet = -1.5, head = feet + height;  // the sensor 1.5 m above the ground
      cv::Mat one = cv::Mat::zeros(camera.height, camera.width, CV_8UC1);
      for (int v = 0; v < camera.height; ++v) {
        for (int u = 0; u < camera.width; ++u) {
          // The pixel's ray in the LiDAR frame meets the board's plane x = range.
          const Eigen::Vector3d ray = to_camera.rotationMatrix().transpose() *
                                      Eigen::Vector3d((u - camera.K()(0, 2)) / camera.K()(0, 0),
                                                      (v - camera.K()(1, 2)) / camera.K()(1, 1), 1.0);
          const Eigen::Vector3d hit = ray * (range / ray.x());
          const double lateral = hit.y() - range * std::tan(centre_deg * kDeg);
          if (std::abs(lateral) <= 0.5 * width && hit.z() >= feet && hit.z() <= head) one.at<std::uint8_t>(v, u) = 1;
        }
      }
      const int e = edge_px > 0 ? static_cast<int>(rng.index(2 * edge_px + 1)) - edge_px : 0;
      const cv::Mat kernel = cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * std::abs(e) + 1, 2 * std::abs(e) + 1));
      if (e > 0) cv::dilate(one, one, kernel);
      if (e < 0) cv::erode(one, one, kernel);
      pair.mask |= one;
      const double phase = rng.uniform(0.0, 0.16);
      for (double el = -30.67; el < 10.0; el += 1.33) {
        const double z = range * std::tan(el * kDeg);
        if (z < feet || z > head) continue;
        for (double az = centre_deg - half_deg - 0.16 + phase; az <= centre_deg + half_deg; az += 0.16) {
          const double lateral = range * std::tan(az * kDeg) - range * std::tan(centre_deg * kDeg);
          if (std::abs(lateral) > 0.5 * width) continue;
          const double r = range / (std::cos(el * kDeg) * std::cos(az * kDeg));
          pair.points.push_back(polar(r, el, az));
          pair.labels.push_back(k);
        }
      }
    }
    pair.people = people;
    pairs.push_back(std::move(pair));
  }
  return pairs;
}

// 100 x 80 camera, f = 100.
CameraModel smallCamera() { return CameraModel::fromK(100, 80, {100, 0, 50, 0, 100, 40, 0, 0, 1}, {}); }

// A person 21 px wide (columns 40-60, rows 30-50) and one ring at elevation 0, 1 m ahead, from
// u = 40 to 60 in steps of 1 px: at lidarToCamera() its ends lie half a step inside the person
// pixels' outline (39.5 and 60.5).
CalibrationPair oneRingPair() {
  CalibrationPair pair;
  pair.mask = cv::Mat::zeros(80, 100, CV_8UC1);
  pair.mask(cv::Rect(40, 30, 21, 21)).setTo(1);
  for (int k = 0; k <= 20; ++k) {
    pair.points.emplace_back(1.0f, static_cast<float>(-(40.0 + k - 50.0) / 100.0), 0.0f);
    pair.labels.push_back(1);
  }
  return pair;
}

std::vector<std::size_t> all(std::size_t n) {
  std::vector<std::size_t> v(n);
  std::iota(v.begin(), v.end(), std::size_t{0});
  return v;
}

}  // namespace

TEST(RingEnds, EachRingOfEachPersonGivesItsTwoEndsByAzimuth) {
  std::vector<Eigen::Vector3f> points;
  std::vector<std::int32_t> labels;
  for (int ring = 0; ring < 3; ++ring) {
    for (int a = 0; a < 5; ++a) {
      points.push_back(polar(10.0, -5.0 + 1.33 * ring, 2.0 + 0.2 * a));
      labels.push_back(1);
    }
  }
  for (int a = 0; a < 2; ++a) {  // a ring of two points: too few to have ends
    points.push_back(polar(10.0, -5.0, -3.0 + 0.2 * a));
    labels.push_back(2);
  }
  points.push_back(polar(10.0, 0.0, 0.0));
  labels.push_back(0);  // not a person
  const std::vector<RingEnd> ends = findRingEnds(points, labels);
  ASSERT_EQ(ends.size(), 6u);
  for (int ring = 0; ring < 3; ++ring) {
    EXPECT_EQ(ends[2 * ring].point, static_cast<std::uint32_t>(5 * ring));
    EXPECT_EQ(ends[2 * ring].neighbour, static_cast<std::uint32_t>(5 * ring + 1));
    EXPECT_EQ(ends[2 * ring + 1].point, static_cast<std::uint32_t>(5 * ring + 4));
    EXPECT_EQ(ends[2 * ring + 1].neighbour, static_cast<std::uint32_t>(5 * ring + 3));
  }
  labels.pop_back();
  EXPECT_TRUE(findRingEnds(points, labels).empty()) << "labels that do not match the points";
}

TEST(RingEnds, TheTermIsZeroForEndsHalfAStepInsideTheOutlineAndGrowsEitherWay) {
  const CameraModel camera = smallCamera();
  const std::vector<CalibrationPair> pairs{oneRingPair()};
  const LossEvaluator plain(camera, pairs, LossConfig{5.0, PixelRule::kBilinear});
  const Extrinsic at = lidarToCamera();
  const LossEvaluator loss = plain.withRingEnds(pairs, at, 1.0);
  EXPECT_EQ(loss.ringEndCount(), 2u);
  EXPECT_NEAR(loss.pairLoss(0, at), 0.0, 1e-5);
  Extrinsic nearer = at;  // the camera 10 % nearer: the row is 10 % wider, ends outside the outline
  nearer.translation = Eigen::Vector3d(0, 0, -0.1);
  Extrinsic farther = at;  // 10 % farther: narrower, ends inside by more than half a step
  farther.translation = Eigen::Vector3d(0, 0, 0.1);
  const double without_ends_farther = plain.pairLoss(0, farther);
  EXPECT_NEAR(without_ends_farther, 0.0, 1e-6) << "the mask loss alone does not see a shrink";
  // Each end ~0.9 px off the same way: the ring's width off by ~1.8 px, weighed kRingWidthWeight.
  EXPECT_GT(loss.pairLoss(0, farther), 0.4);
  EXPECT_GT(loss.pairLoss(0, nearer), 0.4);
  EXPECT_NEAR(loss.withPixelRule(PixelRule::kNearest).pairLoss(0, farther), 0.0, 1e-6) << "the paper's rule";
}

TEST(RingEnds, TheEndsMoveWithTheirPersonToAnotherTimeOffset) {
  // The person of the test above walking right at 1 m/s, 1 m ahead: 2 px in 20 ms. At offset 0
  // its ends lie half a step inside; at +20 ms both are 2 px off (one beyond its outline, one
  // inside by 2.5 px): the ring's middle is 2 px off, |a - b| = 4 px capped at 3, its width
  // right, so the ring-end term is 3 px over its two ends, 1.5, whatever the mask loss does.
  const CameraModel camera = smallCamera();
  CalibrationPair pair = oneRingPair();
  PersonMotion walker;
  walker.label = 1;
  walker.velocity_mps = Eigen::Vector3d(0, -1, 0);  // LiDAR -y: the image's +u
  walker.scans = 3;
  attachMotion(pair, {walker});
  const std::vector<CalibrationPair> pairs{pair};
  const LossEvaluator plain(camera, pairs, LossConfig{5.0, PixelRule::kBilinear, 0.0});
  const Extrinsic at = lidarToCamera();
  const LossEvaluator loss = plain.withRingEnds(pairs, at, 1.0);
  EXPECT_NEAR(loss.pairLoss(0, at) - plain.pairLoss(0, at), 0.0, 1e-5);
  const double moved = loss.withTimeOffset(0.02).pairLoss(0, at) - plain.withTimeOffset(0.02).pairLoss(0, at);
  EXPECT_NEAR(moved, 1.5, 1e-3);
  EXPECT_NEAR(loss.withTimeOffset(0.02).withTimeOffset(0.0).pairLoss(0, at) - plain.pairLoss(0, at), 0.0, 1e-5);
}

TEST(RingEnds, ARingOnAnErodedMaskIsHeldByItsMiddle) {
  // The person of oneRingPair with its mask eroded by 2 px (columns 42-58): at the true pose both
  // ends lie 2 px beyond the outline, |a| = |b| = 2. Charged end by end, a shift of 1 px along
  // the row costs nothing more (1 + 3 = 2 + 2); charged as the ring's middle and width it does:
  // (0 + 0.5 * 3) / 2 ends at the truth, (2 + 0.5 * 3) / 2 a pixel either way.
  const CameraModel camera = smallCamera();
  CalibrationPair pair = oneRingPair();
  pair.mask = cv::Mat::zeros(80, 100, CV_8UC1);
  pair.mask(cv::Rect(42, 32, 17, 17)).setTo(1);
  const std::vector<CalibrationPair> pairs{pair};
  const LossEvaluator plain(camera, pairs, LossConfig{5.0, PixelRule::kBilinear});
  const Extrinsic at = lidarToCamera();
  const LossEvaluator loss = plain.withRingEnds(pairs, at, 1.0);
  ASSERT_EQ(loss.ringEndCount(), 2u);
  const auto ringTerm = [&](double shift_px) {
    Extrinsic moved = at;
    moved.translation = Eigen::Vector3d(shift_px / 100.0, 0, 0);  // f = 100 px, the ring 1 m ahead
    return loss.pairLoss(0, moved) - plain.pairLoss(0, moved);
  };
  EXPECT_NEAR(ringTerm(0.0), 0.75, 1e-4);
  EXPECT_NEAR(ringTerm(1.0), 1.75, 1e-4);
  EXPECT_NEAR(ringTerm(-1.0), 1.75, 1e-4);
}

TEST(RingEnds, WithMasksErodedOrDilatedTheEndsTakeOutTheForwardLean) {
  const CameraModel camera = test_support::fieldsafeCamera(false);
  double lean_without = 0.0, lean_with = 0.0;
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    const std::vector<CalibrationPair> pairs = boardPairs(camera, seed, 2);
    const LossEvaluator plain(camera, pairs, LossConfig{5.0, PixelRule::kBilinear});
    const Extrinsic truth = lidarToCamera();
    const LossEvaluator ends = plain.withRingEnds(pairs, truth, 1.0);
    const auto forward = [&](const LossEvaluator& loss) {
      const Extrinsic fit = LocalRefinement(loss, RefineConfig{}, 1).run(truth, all(pairs.size())).best;
      return poseDifference(fit, truth).translation_cm.z();
    };
    lean_without += forward(plain) / 4.0;
    lean_with += forward(ends) / 4.0;
  }
  EXPECT_GT(lean_without, 0.8) << "the scene should show the lean (cm)";
  EXPECT_LT(std::abs(lean_with), 0.2 * lean_without) << lean_with << " cm against " << lean_without;
}

TEST(RingEnds, APersonBehindTheSensorHasItsEndsWhereItsSpanEnds) {
  std::vector<Eigen::Vector3f> points;
  std::vector<std::int32_t> labels;
  for (int a = 0; a < 5; ++a) {  // azimuths 179.6 .. -179.6 deg: across the wrap
    points.push_back(polar(10.0, 0.0, 179.6 + 0.2 * a));
    labels.push_back(3);
  }
  const std::vector<RingEnd> ends = findRingEnds(points, labels);
  ASSERT_EQ(ends.size(), 2u);
  EXPECT_EQ(ends[0].point, 0u);
  EXPECT_EQ(ends[1].point, 4u);
}

namespace {

// One ring's worth of ends on a 100 x 60 image: points at pixels `pixels` (one per point), all of
// label 1 unless given, the ends found by the caller.
std::vector<Eigen::Vector2f> row(float v, float from, float to, float step) {
  std::vector<Eigen::Vector2f> out;
  for (float u = from; u <= to + 1e-3f; u += step) out.emplace_back(u, v);
  return out;
}

}  // namespace

TEST(RingEnds, EachClusterIsMeasuredAgainstItsOwnRegionNotTheUnion) {
  cv::Mat mask = cv::Mat::zeros(60, 100, CV_8UC1);
  mask(cv::Rect(20, 10, 11, 40)).setTo(1);  // person 1: columns 20-30
  mask(cv::Rect(60, 10, 11, 40)).setTo(1);  // person 2: columns 60-70
  std::vector<Eigen::Vector2f> pixels = row(25.0f, 20.5f, 29.5f, 1.0f);
  const std::vector<Eigen::Vector2f> second = row(25.0f, 60.5f, 69.5f, 1.0f);
  std::vector<std::int32_t> labels(pixels.size(), 1);
  pixels.insert(pixels.end(), second.begin(), second.end());
  labels.resize(pixels.size(), 2);
  const std::uint32_t n = static_cast<std::uint32_t>(second.size());
  const std::vector<RingEnd> ends{{0, 1}, {n - 1, n - 2}, {n, n + 1}, {2 * n - 1, 2 * n - 2}};
  const RingEndSet set = assignRingEnds(mask, labels, ends, pixels);
  ASSERT_EQ(set.ends.size(), 4u);
  ASSERT_EQ(set.outlines.size(), 2u);
  EXPECT_EQ(set.ends[0].side, -1);
  EXPECT_EQ(set.ends[1].side, 1);
  // Each ring's two ends, one after the other: the second is paired with the first.
  EXPECT_FALSE(set.ends[0].pairs_previous);
  EXPECT_TRUE(set.ends[1].pairs_previous);
  EXPECT_FALSE(set.ends[2].pairs_previous) << "another person's ring";
  EXPECT_TRUE(set.ends[3].pairs_previous);
  // Person 1's left end left out (its neighbour at the same column): its right end stands alone.
  std::vector<Eigen::Vector2f> flat = pixels;
  flat[1].x() = flat[0].x();
  const RingEndSet lone = assignRingEnds(mask, labels, ends, flat);
  ASSERT_EQ(lone.ends.size(), 3u);
  EXPECT_FALSE(lone.ends[0].pairs_previous);
  EXPECT_FALSE(lone.ends[1].pairs_previous);
  EXPECT_TRUE(lone.ends[2].pairs_previous);
  EXPECT_NE(set.ends[0].outline, set.ends[2].outline);
  // Person 1's right end at u = 30 lies half a step (0.5 px) inside its own outline at 30.5:
  // no cost; against the union's outline (70.5) it would be 40 px inside.
  const PersonOutline& own = set.outlines[set.ends[1].outline];
  EXPECT_NEAR(ringEndCost(own, 1, 30.0f, 25.0f, 0.5f, 3.0f), 0.0f, 1e-5f);
  EXPECT_NEAR(ringEndCost(own, 1, 29.5f, 25.0f, 0.5f, 3.0f), 0.5f, 1e-5f) << "a step inside";
  EXPECT_NEAR(ringEndCost(own, 1, 31.0f, 25.0f, 0.5f, 3.0f), 1.0f, 1e-5f) << "outside by 0.5 + 0.5";
  EXPECT_NEAR(ringEndCost(own, -1, 19.5f, 25.0f, 0.5f, 3.0f), 0.5f, 1e-5f) << "left end on the outline";
  EXPECT_FLOAT_EQ(ringEndCost(own, 1, 40.0f, 25.0f, 0.5f, 3.0f), 3.0f) << "capped";
  EXPECT_FLOAT_EQ(ringEndCost(own, 1, 29.5f, 5.0f, 0.5f, 3.0f), 3.0f) << "above the person";
}

TEST(RingEnds, TheOutlineFollowsTheRowsAndIsInterpolatedBetweenThem) {
  cv::Mat mask = cv::Mat::zeros(60, 100, CV_8UC1);
  mask(cv::Rect(20, 10, 11, 10)).setTo(1);  // rows 10-19: columns 20-30
  mask(cv::Rect(20, 20, 15, 10)).setTo(1);  // rows 20-29: columns 20-34
  const std::vector<Eigen::Vector2f> pixels = row(19.0f, 21.0f, 29.0f, 1.0f);
  const std::vector<std::int32_t> labels(pixels.size(), 1);
  const RingEndSet set = assignRingEnds(mask, labels, {{8, 7}}, pixels);
  ASSERT_EQ(set.ends.size(), 1u);
  const PersonOutline& o = set.outlines[0];
  EXPECT_EQ(o.first_row, 10);
  EXPECT_FLOAT_EQ(o.right[19 - 10], 30.5f);
  EXPECT_FLOAT_EQ(o.right[20 - 10], 34.5f);
  // Half way between rows 19 and 20 the outline is at 32.5; an end there with its neighbour 1 px
  // inward should lie at 32.0.
  EXPECT_NEAR(ringEndCost(o, 1, 32.0f, 19.5f, 0.5f, 3.0f), 0.0f, 1e-5f);
}

TEST(RingEnds, OutlinesBesideAnotherPersonOrTheImageBorderAndSharedRegionsAreLeftOut) {
  cv::Mat mask = cv::Mat::zeros(60, 100, CV_8UC1);
  mask(cv::Rect(0, 10, 11, 40)).setTo(1);   // person 1 cut by the left border: columns 0-10
  mask(cv::Rect(13, 10, 10, 40)).setTo(1);  // person 2: columns 13-22, 2 px right of person 1
  mask(cv::Rect(50, 10, 30, 40)).setTo(1);  // persons 3 and 4 in one region: columns 50-79
  std::vector<Eigen::Vector2f> pixels;
  std::vector<std::int32_t> labels;
  const auto add = [&](int label, float from, float to) {
    for (const Eigen::Vector2f& p : row(25.0f, from, to, 1.0f)) {
      pixels.push_back(p);
      labels.push_back(label);
    }
  };
  add(1, 0.5f, 9.5f);
  add(2, 13.5f, 21.5f);
  add(3, 50.5f, 63.5f);
  add(4, 65.5f, 78.5f);
  std::vector<RingEnd> ends;
  std::uint32_t first = 0;
  for (int label = 1; label <= 4; ++label) {
    std::uint32_t last = first;
    while (last + 1 < labels.size() && labels[last + 1] == label) ++last;
    ends.push_back({first, first + 1});
    ends.push_back({last, last - 1});
    first = last + 1;
  }
  const RingEndSet set = assignRingEnds(mask, labels, ends, pixels);
  // Persons 3 and 4 share a region (neither outline is known): no ends. Persons 1 and 2 keep all
  // four ends, but their outlines facing each other (2 px apart) and person 1's at the border
  // have no usable column.
  ASSERT_EQ(set.ends.size(), 4u);
  for (const AssignedRingEnd& e : set.ends) EXPECT_LE(labels[e.point], 2);
  const PersonOutline& one = set.outlines[set.ends[0].outline];
  const PersonOutline& two = set.outlines[set.ends[2].outline];
  EXPECT_TRUE(std::isnan(one.left[15]));
  EXPECT_TRUE(std::isnan(one.right[15]));
  EXPECT_TRUE(std::isnan(two.left[15]));
  EXPECT_FLOAT_EQ(two.right[15], 22.5f);
  EXPECT_FLOAT_EQ(ringEndCost(one, 1, 9.5f, 25.0f, 0.5f, 3.0f), 3.0f);
}

TEST(RingEnds, AClusterOutsideEveryRegionHasNoEnds) {
  cv::Mat mask = cv::Mat::zeros(60, 100, CV_8UC1);
  mask(cv::Rect(20, 10, 11, 40)).setTo(1);
  const std::vector<Eigen::Vector2f> pixels = row(25.0f, 60.0f, 70.0f, 1.0f);  // a false cluster
  const std::vector<std::int32_t> labels(pixels.size(), 1);
  EXPECT_TRUE(assignRingEnds(mask, labels, {{0, 1}}, pixels).ends.empty());
}

TEST(RingEnds, WithRingEndsNeedsTheEvaluatorsOwnPairs) {
  const CameraModel camera = smallCamera();
  CalibrationPair pair;
  pair.mask = cv::Mat::zeros(80, 100, CV_8UC1);
  pair.mask(cv::Rect(40, 30, 21, 21)).setTo(1);
  pair.points = {Eigen::Vector3f(1, 0, 0)};
  pair.labels = {1};
  const LossEvaluator loss(camera, {pair}, LossConfig{});
  EXPECT_THROW(loss.withRingEnds({pair, pair}, lidarToCamera(), 1.0), std::invalid_argument);
  EXPECT_EQ(loss.withRingEnds({pair}, lidarToCamera(), 1.0).ringEndCount(), 0u) << "one point: no ring";
}

TEST(RingEnds, PointsSpreadOverElevationsAreNoRing) {
  // Points at random heights on a person (a solid-state pattern, or the unit tests' sparse
  // random pairs) chain into one run of small elevation gaps; its extreme azimuths are not where
  // any scan line leaves the person, so it has no ends. One real ring beside it keeps its two.
  Rng rng(3);
  std::vector<Eigen::Vector3f> points;
  std::vector<std::int32_t> labels;
  for (int k = 0; k < 400; ++k) {
    points.push_back(polar(10.0, rng.uniform(-10.0, 0.0), rng.uniform(1.0, 4.0)));
    labels.push_back(1);
  }
  EXPECT_TRUE(findRingEnds(points, labels).empty());
  for (int a = 0; a < 6; ++a) {
    points.push_back(polar(10.0, 3.0, -4.0 + 0.2 * a));
    labels.push_back(2);
  }
  EXPECT_EQ(findRingEnds(points, labels).size(), 2u);
}

TEST(RingEnds, AFewChanceRingsAmongPointsAtRandomHeightsAreNoScanLines) {
  // 12 points at scattered heights on a person (at least 0.4 deg apart, so no run covers any of
  // its span) and one ring of 4 points among them (a sparse cluster where a few points share an
  // elevation by chance): most of its points lie on no ring, so it has no ends. A person on scan
  // lines with a few stray points keeps its rings' ends.
  Rng rng(5);
  std::vector<Eigen::Vector3f> points;
  std::vector<std::int32_t> labels;
  for (int k = 0; k < 12; ++k) {
    points.push_back(polar(10.0, -10.0 + 0.6 * k + rng.uniform(-0.1, 0.1), rng.uniform(1.0, 4.0)));
    labels.push_back(1);
  }
  for (int a = 0; a < 4; ++a) {
    points.push_back(polar(10.0, -5.7, 1.5 + 0.2 * a));
    labels.push_back(1);
  }
  EXPECT_TRUE(findRingEnds(points, labels).empty());
  for (int ring = 0; ring < 4; ++ring) {
    for (int a = 0; a < 6; ++a) {
      points.push_back(polar(12.0, -8.0 + 1.33 * ring, -6.0 + 0.2 * a));
      labels.push_back(2);
    }
  }
  for (const double elevation : {-7.3, -6.0, -4.7}) {  // between its rings
    points.push_back(polar(12.0, elevation, rng.uniform(-6.0, -5.0)));
    labels.push_back(2);
  }
  EXPECT_EQ(findRingEnds(points, labels).size(), 8u);
}

TEST(RingEnds, TheDefaultRunReadsThemAndThePaperModeDoesNot) {
  const CameraModel camera = test_support::fieldsafeCamera(false);
  const Extrinsic truth = test_support::fieldsafeTruth();
  test_support::SyntheticPairsOptions o;
  o.pairs = 20;
  o.points_per_person = 240;  // dense enough that every ring holds several points a person
  std::vector<CalibrationPair> pairs = test_support::makeSyntheticPairs(camera, truth, o);
  test_support::snapToRings(pairs, 1.33);
  CalibrationConfig config;
  config.num_threads = 1;
  config.time_offset.mode = TimeOffsetMode::kNone;
  config.evolution.max_iterations = 5;
  config.evolution.population_size = 40;
  EXPECT_GT(refineFrom(camera, pairs, config, truth, 0.0).ring_ends, 0u);
  config.refine.ring_end_weight = 0.0;
  EXPECT_EQ(refineFrom(camera, pairs, config, truth, 0.0).ring_ends, 0u);
  config.refine.ring_end_weight = 1.0;
  config.refine.mode = RefineMode::kNone;
  EXPECT_EQ(calibrate(camera, pairs, config).ring_ends, 0u) << "the paper's method alone";
}

TEST(RingEnds, AnEvaluatorOverSomePairsReadsEachAsTheWholeDoes) {
  // The bootstrap reads its pairs through an evaluator over them alone (LossEvaluator::ofPairs):
  // every pair, its motion and its ring ends must read exactly as in the evaluator it came from,
  // at the offset it had and at any other.
  const CameraModel camera = test_support::fieldsafeCamera(false);
  std::vector<CalibrationPair> pairs = boardPairs(camera, 3, 1);
  for (CalibrationPair& pair : pairs) {
    pair.cloud_stamp_s = pair.stamp_s;
    std::vector<PersonMotion> motion;
    for (const std::int32_t label : std::set<std::int32_t>(pair.labels.begin(), pair.labels.end())) {
      PersonMotion m;
      m.label = label;
      m.velocity_mps = Eigen::Vector3d(-2.0, 0.3 * label, 0.0);
      m.scans = 5;
      motion.push_back(m);
    }
    attachMotion(pair, motion);
  }
  const LossEvaluator plain(camera, pairs, LossConfig{5.0, PixelRule::kBilinear, 0.05});
  ASSERT_TRUE(plain.hasMotion());
  const LossEvaluator whole = plain.withRingEnds(pairs, lidarToCamera(), 1.0);
  ASSERT_GT(whole.ringEndCount(), 0u);
  const std::vector<std::size_t> picked = {17, 2, 2, 39, 0};
  const LossEvaluator part = whole.ofPairs(picked);
  ASSERT_EQ(part.pairCount(), picked.size());
  const std::vector<std::size_t> local = {0, 1, 2, 3, 4};
  Extrinsic off = lidarToCamera();
  off.translation.x() += 0.03;
  for (const Extrinsic& e : {lidarToCamera(), off}) {
    EXPECT_EQ(part.loss(e, local), whole.loss(e, picked));
    EXPECT_EQ(part.withTimeOffset(0.02).loss(e, {3, 1}), whole.withTimeOffset(0.02).loss(e, {39, 2}));
    for (std::size_t k = 0; k < picked.size(); ++k) EXPECT_EQ(part.pairLoss(k, e), whole.pairLoss(picked[k], e));
  }
  EXPECT_EQ(part.centroid(local), whole.centroid(picked));
  EXPECT_THROW(whole.ofPairs({pairs.size()}), std::invalid_argument);
}
