// How the synthetic vehicle drives (issue 21): the steady drive exactly as before, the field
// profile's stops, speed changes and turns, the degenerate drive (straight, one speed, people
// standing), and the people's motion relative to the LiDAR.
#include "thermal_lidar_calibration/synthetic/synthetic_rig.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace syn = thermal_lidar_calibration::synthetic;

namespace {

syn::SceneConfig fieldScene(double duration_s) {
  syn::SceneConfig scene;
  scene.duration_s = duration_s;
  scene.speed_mps = 2.5;
  scene.speed_profile = syn::SpeedProfile::kField;
  return scene;
}

// Is the person's axis in the camera's image (with a margin) and within the detectors' range?
bool inView(const syn::SyntheticRig& rig, const Eigen::Vector3d& p_lidar) {
  const syn::RigPreset& preset = rig.config().rig;
  if (p_lidar.head<2>().norm() > rig.config().detector.detection_range_m) return false;
  const Eigen::Vector3d pc = preset.truth.rotationMatrix() * p_lidar + preset.truth.translation;
  if (pc.z() <= 0.5) return false;
  const Eigen::Vector2d px = preset.camera.project(pc);
  constexpr double kMarginPx = 60;  // a person is about this wide at the detection range
  return px.x() > -kMarginPx && px.x() < preset.camera.width + kMarginPx && px.y() > -kMarginPx &&
         px.y() < preset.camera.height + kMarginPx;
}

}  // namespace

// Values the generator gave before issue 21 (commit 845fbdc, same configurations): the steady
// drive, the default, must render exactly as it did (the default demo bag is also byte-for-byte
// the same: md5sum of `make_synthetic_bag --output X.bag` before and after).
TEST(SyntheticDrive, TheSteadyDriveIsTheDriveAsItWas) {
  struct Pose {
    double t, x, y, yaw;
  };
  struct Frame {
    int index;
    std::size_t points;
    double sx, sy, sz;
    int mask_px;
    double image_sum;
  };
  struct Expected {
    std::string rig;
    std::vector<Pose> poses;
    std::vector<Frame> frames;
  };
  const std::vector<Expected> expected = {
      {"fieldsafe",
       {{0.0, 0.0, 0.0, -2.804083409266}, {7.3, -17.220378346998, -6.043266466592, -2.804083409266},
        {41.05, -100.412494968521, -11.278410488403, -2.864083409266},
        {99.9, -204.515232394292, -104.351972639476, -2.730750075933},
        {119.9, -248.278070632949, -127.710843831948, -2.437416742600}},
       {{50, 36, 592.988326, -90.211865, -37.941111, 879, 29020993},
        {300, 22, 375.866905, 130.657994, -24.029958, 1136, 28084670},
        {525, 34, 727.180281, -9.844778, -35.587305, 1600, 28282729},
        {1050, 102, 1205.988132, -154.060982, -91.051079, 1632, 29996887}}},
      {"ms2",
       {{0.0, 0.0, 0.0, 0.053693100354}, {7.3, 29.157919055452, 1.567085305818, 0.053693100354},
        {41.05, 160.070855458639, -6.315454935632, 0.460359767020},
        {99.9, 357.428019694245, 106.278459551173, 0.707026433687},
        {119.9, 430.835313418018, 135.249640184574, 0.720359767020}},
       {{175, 21, 434.132124, 3.496175, -20.804346, 468, 11873278},
        {650, 20, 313.657040, -71.044768, -15.750186, 454, 12020363},
        {975, 42, 497.376948, -13.267183, -35.710165, 1525, 12734176}}},
  };
  for (const Expected& e : expected) {
    syn::SyntheticConfig config;
    config.rig = syn::rigByName(e.rig);
    config.seed = 3;
    config.frames = 1200;
    const syn::SyntheticRig rig(config);
    for (const Pose& p : e.poses) {
      const syn::VehiclePose pose = rig.scene().vehicleAt(p.t);
      EXPECT_NEAR(pose.xy.x(), p.x, 1e-9) << e.rig << " t " << p.t;
      EXPECT_NEAR(pose.xy.y(), p.y, 1e-9) << e.rig << " t " << p.t;
      EXPECT_NEAR(pose.yaw_rad, p.yaw, 1e-9) << e.rig << " t " << p.t;
    }
    for (const Frame& f : e.frames) {
      const syn::SyntheticFrame frame = rig.render(f.index);
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      for (const auto& q : frame.cluster_points) sum += q.cast<double>();
      EXPECT_EQ(frame.cluster_points.size(), f.points) << e.rig << " frame " << f.index;
      EXPECT_NEAR(sum.x(), f.sx, 1e-5) << e.rig << " frame " << f.index;
      EXPECT_NEAR(sum.y(), f.sy, 1e-5) << e.rig << " frame " << f.index;
      EXPECT_NEAR(sum.z(), f.sz, 1e-5) << e.rig << " frame " << f.index;
      EXPECT_EQ(cv::countNonZero(frame.mask), f.mask_px) << e.rig << " frame " << f.index;
      EXPECT_EQ(cv::sum(frame.image)[0], f.image_sum) << e.rig << " frame " << f.index;
    }
  }
}

TEST(SyntheticDrive, TheFieldProfileStopsAndChangesSpeedWithoutJumps) {
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const syn::Scene scene(fieldScene(120.0), seed);
    const syn::DriveSchedule& drive = scene.schedule();
    constexpr double kDt = 0.01;
    const double max_accel = 0.2 * 2.5;  // the tractor's bound
    double stopped_s = 0.0, fastest = 0.0, slowest_moving = 1e9;
    syn::VehicleMotion before = scene.vehicleMotionAt(-kDt);
    for (double t = 0.0; t < 120.0; t += kDt) {
      const syn::VehicleMotion now = scene.vehicleMotionAt(t);
      EXPECT_LE(std::abs(now.speed_mps - before.speed_mps), max_accel * kDt * 1.01 + 1e-12) << "t " << t;
      // Positions and heading move continuously, by what speed and yaw rate allow.
      EXPECT_LE((now.pose.xy - before.pose.xy).norm(), drive.maxSpeed() * kDt + 1e-6) << "t " << t;
      EXPECT_LE(std::abs(now.pose.yaw_rad - before.pose.yaw_rad), 0.5 * kDt) << "t " << t;
      // The arc length is the speed's integral.
      EXPECT_NEAR((drive.arcLengthAt(t) - drive.arcLengthAt(t - kDt)) / kDt, drive.speedAt(t - 0.5 * kDt), 1e-4);
      if (now.speed_mps < 0.01) stopped_s += kDt;
      if (now.speed_mps >= 0.3) slowest_moving = std::min(slowest_moving, now.speed_mps);
      fastest = std::max(fastest, now.speed_mps);
      before = now;
    }
    EXPECT_GT(stopped_s, 1.5) << "seed " << seed;                 // it stops
    EXPECT_GT(fastest - slowest_moving, 0.8) << "seed " << seed;  // and drives at several speeds
    EXPECT_LE(fastest, 3.0 + 1e-9) << "seed " << seed;            // 0-3 m/s for the FieldSAFE-like rig
  }
  EXPECT_THROW(syn::speedProfileByName("fast"), std::invalid_argument);
}

// The field drive turns while people are in view (the steady one never does: see the next test).
TEST(SyntheticDrive, OnTheFieldProfileTheVehicleTurnsWhilePeopleAreInView) {
  syn::SyntheticConfig config;
  config.seed = 2;
  config.frames = 1200;
  config.scene.speed_profile = syn::SpeedProfile::kField;
  const syn::SyntheticRig rig(config);
  int in_view = 0, turning = 0;
  for (int i = 0; i < config.frames; ++i) {
    const double stamp = rig.stampOf(i);
    const double yaw_rate = rig.scene().vehicleMotionAt(stamp - config.start_stamp_s).yaw_rate_radps;
    for (const syn::PersonTrack& person : rig.scene().people()) {
      if (!inView(rig, rig.personMotion(person.id, stamp).position_m)) continue;
      ++in_view;
      if (std::abs(yaw_rate) > 0.02) ++turning;
    }
  }
  ASSERT_GT(in_view, 100);
  EXPECT_GT(turning, in_view / 4) << turning << " of " << in_view;
}

// The drive whose timing cannot be told from the translation along the travel: steady speed,
// people standing (--walking-fraction 0), and nobody in view during a turn, on both rigs.
TEST(SyntheticDrive, TheDegenerateDriveIsStraightAndSteadyWheneverSomeoneIsInView) {
  for (const std::string rig_name : {"fieldsafe", "ms2"}) {
    for (std::uint64_t seed = 1; seed <= 5; ++seed) {
      syn::SyntheticConfig config;
      config.rig = syn::rigByName(rig_name);
      config.seed = seed;
      config.frames = 1200;
      config.scene.walking_fraction = 0.0;
      const syn::SyntheticRig rig(config);
      const double speed = config.rig.vehicle_speed_mps;
      int in_view = 0;
      for (int i = 0; i < config.frames; ++i) {
        const double stamp = rig.stampOf(i);
        const syn::VehicleMotion vehicle = rig.scene().vehicleMotionAt(stamp - config.start_stamp_s);
        for (const syn::PersonTrack& person : rig.scene().people()) {
          const syn::PersonMotion m = rig.personMotion(person.id, stamp);
          if (!inView(rig, m.position_m)) continue;
          ++in_view;
          EXPECT_EQ(vehicle.yaw_rate_radps, 0.0) << rig_name << " seed " << seed << " frame " << i;
          EXPECT_NEAR(m.velocity_mps.x(), -speed, 1e-9) << rig_name << " seed " << seed << " frame " << i;
          EXPECT_NEAR(m.velocity_mps.y(), 0.0, 1e-9) << rig_name << " seed " << seed << " frame " << i;
        }
      }
      EXPECT_GT(in_view, 100) << rig_name << " seed " << seed;
    }
  }
}

TEST(SyntheticDrive, PersonMotionIsTheRateOfChangeOfThePersonsPlaceInTheLidarFrame) {
  syn::SyntheticConfig config;
  config.seed = 4;
  config.frames = 1200;
  config.scene.speed_profile = syn::SpeedProfile::kField;
  config.scene.walking_fraction = 1.0;
  const syn::SyntheticRig rig(config);
  constexpr double kH = 1e-3;
  int checked = 0, walking = 0, turning = 0;
  // From frame 1: before 0 s the vehicle drove straight, so the yaw rate steps at 0 s.
  for (int i = 1; i < config.frames; i += 7) {
    const double stamp = rig.stampOf(i);
    const syn::VehicleMotion vehicle = rig.scene().vehicleMotionAt(stamp - config.start_stamp_s);
    for (const syn::PersonTrack& person : rig.scene().people()) {
      const syn::PersonMotion m = rig.personMotion(person.id, stamp);
      if (m.position_m.head<2>().norm() > 40.0) continue;
      const Eigen::Vector3d numeric =
          (rig.personMotion(person.id, stamp + kH).position_m - rig.personMotion(person.id, stamp - kH).position_m) /
          (2.0 * kH);
      // The field drive's position follows 0.1 m chords while its heading turns smoothly (their
      // directions differ by up to half a chord's turn, 0.005 rad: 1.5 cm/s at 3 m/s), and its
      // yaw rate is constant along each chord, stepping at the next (up to 2 cm/s for a person
      // 40 m away when the difference straddles a step).
      EXPECT_LT((m.velocity_mps - numeric).norm(), 0.04) << "frame " << i << " person " << person.id;
      EXPECT_EQ(m.person_id, person.id);
      EXPECT_NEAR(m.position_m.z(), rig.groundZ() + 0.5 * person.height_m, 1e-12);
      ++checked;
      if (person.velocityAt(stamp - config.start_stamp_s).norm() > 0.2) ++walking;
      if (std::abs(vehicle.yaw_rate_radps) > 0.02) ++turning;
    }
  }
  EXPECT_GT(checked, 100);
  EXPECT_GT(walking, checked / 4);
  EXPECT_GT(turning, 10);
  EXPECT_THROW(rig.personMotion(0, rig.stampOf(0)), std::invalid_argument);
  EXPECT_THROW(rig.personMotion(1000, rig.stampOf(0)), std::invalid_argument);
}

// The motion describes the rendered people: a person's LiDAR points sit around its position.
TEST(SyntheticDrive, PersonMotionPositionIsWhereThePersonsPointsAre) {
  syn::SyntheticConfig config;
  config.seed = 4;
  config.frames = 600;
  config.scene.speed_profile = syn::SpeedProfile::kField;
  const syn::SyntheticRig rig(config);
  int people = 0;
  for (int i = 0; i < config.frames; i += 25) {
    const syn::SyntheticFrame f = rig.render(i);
    for (const syn::PersonInFrame& p : f.people) {
      if (!p.in_cluster) continue;
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      int n = 0;
      for (std::size_t k = 0; k < f.cluster_points.size(); ++k) {
        if (f.cluster_labels[k] != p.person_id) continue;
        sum += f.cluster_points[k].cast<double>();
        ++n;
      }
      if (n < 10) continue;
      const Eigen::Vector3d centre = rig.personMotion(p.person_id, f.stamp_s).position_m;
      // The points lie on the side facing the LiDAR, within a body's half width of the axis.
      EXPECT_LT((sum / n - centre).head<2>().norm(), 0.3) << "frame " << i << " person " << p.person_id;
      ++people;
    }
  }
  EXPECT_GT(people, 5);
}
