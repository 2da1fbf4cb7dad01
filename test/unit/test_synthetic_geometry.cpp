// Primitives, the person body and the LiDAR beam pattern of the synthetic rig.
#include "thermal_lidar_calibration/synthetic/body_model.hpp"
#include "thermal_lidar_calibration/synthetic/lidar_model.hpp"
#include "thermal_lidar_calibration/synthetic/lidar_scanner.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace tlc = thermal_lidar_calibration::synthetic;

namespace {
constexpr double kDeg = M_PI / 180.0;

tlc::Ray rayFrom(const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
  tlc::Ray r;
  r.origin = o;
  r.direction = d.normalized();
  return r;
}
}  // namespace

TEST(SyntheticGeometry, CapsuleSideAndCapHits) {
  const tlc::Capsule cap{Eigen::Vector3d(5, 0, 0), Eigen::Vector3d(5, 0, 2), 0.5};
  double t = 0;
  ASSERT_TRUE(tlc::intersectCapsule(cap, rayFrom({0, 0, 1}, {1, 0, 0}), &t));
  EXPECT_NEAR(t, 4.5, 1e-9);  // side of the cylinder
  ASSERT_TRUE(tlc::intersectCapsule(cap, rayFrom({5, 0, 10}, {0, 0, -1}), &t));
  EXPECT_NEAR(t, 7.5, 1e-9);  // top cap, straight down the axis
  ASSERT_TRUE(tlc::intersectCapsule(cap, rayFrom({0, 0, -0.2}, {1, 0, 0}), &t));
  EXPECT_NEAR(t, 5.0 - std::sqrt(0.25 - 0.04), 1e-9);  // bottom cap below the segment
  EXPECT_FALSE(tlc::intersectCapsule(cap, rayFrom({0, 0, 1}, {-1, 0, 0}), &t));
  EXPECT_FALSE(tlc::intersectCapsule(cap, rayFrom({0, 0.6, 1}, {1, 0, 0}), &t));
}

TEST(SyntheticGeometry, EllipsoidAndPlaneHits) {
  const tlc::Ellipsoid e{Eigen::Vector3d(10, 0, 0), Eigen::Matrix3d::Identity(), Eigen::Vector3d(1, 2, 3)};
  double t = 0;
  ASSERT_TRUE(tlc::intersectEllipsoid(e, rayFrom({0, 0, 0}, {1, 0, 0}), &t));
  EXPECT_NEAR(t, 9.0, 1e-9);
  ASSERT_TRUE(tlc::intersectEllipsoid(e, rayFrom({10, 0, 10}, {0, 0, -1}), &t));
  EXPECT_NEAR(t, 7.0, 1e-9);
  ASSERT_TRUE(tlc::intersectHorizontalPlane(-1.9, rayFrom({0, 0, 0}, {1, 0, -1}), &t));
  EXPECT_NEAR(t, 1.9 * std::sqrt(2.0), 1e-9);
  EXPECT_FALSE(tlc::intersectHorizontalPlane(-1.9, rayFrom({0, 0, 0}, {1, 0, 1}), &t));
}

TEST(SyntheticGeometry, PersonBodyHasTheRequestedHeightAndWidth) {
  for (double h : {1.55, 1.75, 1.95}) {
    tlc::BodyPose pose;
    pose.ground_xy = Eigen::Vector2d(8, 2);
    pose.height_m = h;
    const tlc::Solid body = tlc::makePersonBody(pose);
    double t = 0;
    // Straight down onto the head: the top is at the requested height.
    ASSERT_TRUE(body.intersect(rayFrom({8, 2, 5}, {0, 0, -1}), 1e9, &t));
    EXPECT_NEAR(5.0 - t, h, 0.01);
    // Horizontal ray at the waist hits the torso; one at knee height hits a leg.
    EXPECT_TRUE(body.intersect(rayFrom({0, 2, 0.6 * h}, {1, 0, 0}), 1e9, &t));
    EXPECT_TRUE(body.intersect(rayFrom({0, 2.0 + 0.09 * h / 1.75, 0.25 * h}, {1, 0, 0}), 1e9, &t));
    // Nothing a metre beside it.
    EXPECT_FALSE(body.intersect(rayFrom({0, 3.2, 0.6 * h}, {1, 0, 0}), 1e9, &t));
    EXPECT_LT(body.boundingRadius(), 0.6 * h + 0.4);
  }
}

TEST(SyntheticGeometry, TransformedSolidMovesWithItsPose) {
  const tlc::Solid post = tlc::makePost(Eigen::Vector2d(0, 0), 1.5, 0.1);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translate(Eigen::Vector3d(10, 0, -1.9));
  const tlc::Solid moved = post.transformed(T);
  double t = 0;
  ASSERT_TRUE(moved.intersect(rayFrom({0, 0, -1.0}, {1, 0, 0}), 1e9, &t));
  EXPECT_NEAR(t, 9.9, 1e-9);
}

TEST(SyntheticLidar, Hdl32eBeamPatternMatchesTheSpec) {
  const tlc::LidarModel m = tlc::LidarModel::hdl32e();
  ASSERT_EQ(m.beamCount(), 32);
  EXPECT_NEAR(m.elevations_rad.front() / kDeg, -30.67, 1e-9);
  EXPECT_NEAR(m.elevations_rad.back() / kDeg, 10.67, 1e-9);
  for (int b = 1; b < 32; ++b) {
    EXPECT_NEAR((m.elevations_rad[b] - m.elevations_rad[b - 1]) / kDeg, 1.33, 0.01);
  }
  EXPECT_NEAR(360.0 / m.azimuth_count, 0.166, 0.001);
  const int quarter = m.azimuth_count / 4;
  const Eigen::Vector3d d = m.direction(0, quarter);
  EXPECT_NEAR(d.norm(), 1.0, 1e-12);
  EXPECT_NEAR(m.azimuthRad(quarter), M_PI / 2, 0.2 * kDeg);  // about a quarter turn = +y (left)
  EXPECT_NEAR(d.y(), std::cos(30.67 * kDeg) * std::sin(m.azimuthRad(quarter)), 1e-12);
  EXPECT_NEAR(d.z(), std::sin(-30.67 * kDeg), 1e-12);
}

TEST(SyntheticLidar, Vlp16BeamPatternMatchesTheSpec) {
  const tlc::LidarModel m = tlc::LidarModel::vlp16();
  ASSERT_EQ(m.beamCount(), 16);
  for (int b = 0; b < 16; ++b) EXPECT_NEAR(m.elevations_rad[b] / kDeg, -15.0 + 2.0 * b, 1e-9);
  EXPECT_NEAR(360.0 / m.azimuth_count, 0.2, 1e-9);
}

TEST(SyntheticLidar, ScanHitsGroundRingsAndAPostWithTheBeamElevations) {
  const tlc::LidarModel m = tlc::LidarModel::hdl32e();
  tlc::WorldObject post;
  post.solid = tlc::makePost(Eigen::Vector2d(10, 0), 1.8, 0.15);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translate(Eigen::Vector3d(0, 0, -1.9));
  post.solid = post.solid.transformed(T);
  post.clutter_id = 1;
  const auto returns = tlc::castLidarScan(m, {post}, -1.9);
  int post_hits = 0;
  for (const auto& r : returns) {
    const double el = std::atan2(r.point.z(), r.point.head<2>().norm());
    EXPECT_NEAR(el, m.elevations_rad[r.beam], 1e-5);
    if (r.object == 0) {
      ++post_hits;
      EXPECT_NEAR(r.point.head<2>().norm(), 9.85, 0.16);
    } else {
      EXPECT_NEAR(r.point.z(), -1.9, 1e-4);  // ground
    }
  }
  // About 1.8 m / (10 m * 1.33 deg) ~ 8 beams times ~0.3 m / (10 m * 0.166 deg) ~ 10 azimuths.
  EXPECT_GT(post_hits, 40);
  EXPECT_LT(post_hits, 140);
  const double nearest_ring = 1.9 / std::tan(30.67 * kDeg);
  double min_ground = 1e9;
  for (const auto& r : returns) {
    if (r.object < 0) min_ground = std::min(min_ground, static_cast<double>(r.point.head<2>().norm()));
  }
  EXPECT_NEAR(min_ground, nearest_ring, 1e-3);
}
