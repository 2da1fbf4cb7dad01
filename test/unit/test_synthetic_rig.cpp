// The synthetic rig end to end (no ROS): projection consistency of clusters and masks under the
// true extrinsic, people counts in view, determinism, presets, noise options.
#include "thermal_lidar_calibration/core/camera_model.hpp"
#include "thermal_lidar_calibration/core/dataset_builder.hpp"
#include "thermal_lidar_calibration/synthetic/synthetic_rig.hpp"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>

namespace tlc = thermal_lidar_calibration;
namespace syn = thermal_lidar_calibration::synthetic;

namespace {

// Mean and max L1 distance (px) from each in-image projected cluster point to the nearest mask
// pixel; also counts points that project inside the image.
struct ProjectionStats {
  double mean_l1 = 0.0;
  double max_l1 = 0.0;
  int points = 0;
};

ProjectionStats projectionStats(const syn::SyntheticFrame& frame, const syn::RigPreset& rig) {
  ProjectionStats stats;
  cv::Mat background = frame.mask == 0;  // 255 where no person
  cv::Mat dist;
  cv::distanceTransform(background, dist, cv::DIST_L1, 3);
  const Eigen::Matrix3d R = rig.truth.rotationMatrix();
  double sum = 0.0;
  for (const auto& p : frame.cluster_points) {
    const Eigen::Vector3d pc = R * p.cast<double>() + rig.truth.translation;
    if (pc.z() <= 0.0) continue;
    const Eigen::Vector2d px = rig.camera.project(pc);
    const int u = static_cast<int>(std::lround(px.x())), v = static_cast<int>(std::lround(px.y()));
    if (u < 0 || v < 0 || u >= rig.camera.width || v >= rig.camera.height) continue;
    const double d = dist.at<float>(v, u);
    sum += d;
    stats.max_l1 = std::max(stats.max_l1, d);
    ++stats.points;
  }
  if (stats.points > 0) stats.mean_l1 = sum / stats.points;
  return stats;
}

syn::SyntheticConfig smallConfig(const std::string& rig, int frames) {
  syn::SyntheticConfig config;
  config.rig = syn::rigByName(rig);
  config.frames = frames;
  config.seed = 7;
  return config;
}

// A person standing at (x, y) in the LiDAR frame of the given rig.
syn::WorldObject personAt(const syn::SyntheticRig& rig, double x, double y, int id) {
  syn::BodyPose pose;
  pose.ground_xy = Eigen::Vector2d(x, y);
  pose.height_m = 1.75;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translate(Eigen::Vector3d(0, 0, rig.groundZ()));
  syn::WorldObject obj;
  obj.solid = syn::makePersonBody(pose).transformed(T);
  obj.person_id = id;
  obj.grey_level = 200;
  return obj;
}

}  // namespace

TEST(SyntheticRig, PixelRaysRoundTripThroughTheLensModel) {
  for (const std::string name : {"fieldsafe", "ms2"}) {
    syn::SyntheticRig rig(smallConfig(name, 1));
    EXPECT_LT(rig.renderer().maxRoundTripErrorPx(), 1e-6) << name;
  }
}

TEST(SyntheticRig, FieldsafeTruthIsARotationNearTheDatasetValues) {
  const syn::RigPreset rig = syn::fieldsafeRig();
  const Eigen::Matrix3d R = rig.truth.rotationMatrix();
  EXPECT_NEAR((R * R.transpose() - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-9);
  EXPECT_NEAR(R.determinant(), 1.0, 1e-9);
  EXPECT_NEAR(R(0, 1), -0.9994, 2e-3);
  EXPECT_NEAR(R(2, 0), 0.9672, 2e-3);
  EXPECT_NEAR(rig.truth.translation.x(), 0.443, 1e-12);
  // The optical axis in the LiDAR frame looks forward and 10-20 deg down.
  const Eigen::Vector3d axis = R.row(2).transpose();
  EXPECT_GT(axis.x(), 0.9);
  const double down_deg = -std::asin(axis.z()) * 180.0 / M_PI;
  EXPECT_GT(down_deg, 10.0);
  EXPECT_LT(down_deg, 20.0);
}

TEST(SyntheticRig, CountsPeopleInViewAndAllRound) {
  syn::SyntheticRig rig(smallConfig("fieldsafe", 1));
  // In front (in view), behind (LiDAR only), and beyond the detection range.
  const std::vector<syn::WorldObject> objects{personAt(rig, 10.0, 1.0, 3), personAt(rig, -8.0, 2.0, 5),
                                              personAt(rig, 45.0, 0.0, 9)};
  const syn::SyntheticFrame frame = rig.renderSnapshot(objects, 0, 1.6e9);
  EXPECT_EQ(frame.counts.mask_people, 1);
  EXPECT_EQ(frame.counts.cluster_people, 2);
  ASSERT_EQ(frame.people.size(), 2u);  // within detection range
  EXPECT_EQ(frame.people[0].mask_id, 1);
  EXPECT_EQ(frame.people[1].mask_id, 0);
  for (const auto label : frame.cluster_labels) EXPECT_TRUE(label == 3 || label == 5);
  // The far person is still warm in the thermal image though not in the mask.
  EXPECT_GT(cv::countNonZero(frame.image > 150), cv::countNonZero(frame.mask));
}

TEST(SyntheticRig, CleanClustersProjectOntoTheMask) {
  for (const std::string name : {"fieldsafe", "ms2"}) {
    syn::SyntheticConfig config = smallConfig(name, 400);
    syn::SyntheticRig rig(config);
    double sum = 0.0;
    int points = 0, frames_checked = 0;
    double worst = 0.0;
    for (int i = 0; i < config.frames; i += 7) {
      const syn::SyntheticFrame frame = rig.render(i);
      if (frame.counts.mask_people != frame.counts.cluster_people || frame.counts.mask_people == 0) continue;
      const ProjectionStats s = projectionStats(frame, config.rig);
      sum += s.mean_l1 * s.points;
      points += s.points;
      worst = std::max(worst, s.max_l1);
      ++frames_checked;
    }
    ASSERT_GT(frames_checked, 5) << name;
    ASSERT_GT(points, 200) << name;
    const double mean = sum / points;
    std::printf("[%s] equal-count frames checked %d, points %d, mean L1 %.3f px, max %.1f px\n", name.c_str(),
                frames_checked, points, mean, worst);
    EXPECT_LT(mean, 0.25) << name;
    EXPECT_LE(worst, 2.0) << name;
  }
}

TEST(SyntheticRig, SameSeedSameFramesOtherSeedOtherFrames) {
  syn::SyntheticConfig config = smallConfig("fieldsafe", 200);
  config.noise = syn::NoiseConfig::realistic();
  config.full_cloud = true;
  const syn::SyntheticRig a(config), b(config);
  config.seed = 8;
  const syn::SyntheticRig c(config);
  for (int i : {0, 57, 123}) {
    const syn::SyntheticFrame fa = a.render(i), fb = b.render(i), fc = c.render(i);
    EXPECT_EQ(cv::norm(fa.image, fb.image, cv::NORM_INF), 0.0);
    EXPECT_EQ(cv::norm(fa.mask, fb.mask, cv::NORM_INF), 0.0);
    ASSERT_EQ(fa.cluster_points.size(), fb.cluster_points.size());
    for (std::size_t k = 0; k < fa.cluster_points.size(); ++k) {
      EXPECT_EQ(fa.cluster_points[k], fb.cluster_points[k]);
      EXPECT_EQ(fa.cluster_labels[k], fb.cluster_labels[k]);
    }
    EXPECT_EQ(fa.full_points.size(), fb.full_points.size());
    EXPECT_GT(cv::norm(fa.image, fc.image, cv::NORM_L1), 0.0);
  }
}

TEST(SyntheticRig, DefaultDriveYieldsAboutSixtyGatedPairs) {
  syn::SyntheticConfig config;  // the generator's defaults
  const auto start = std::chrono::steady_clock::now();
  syn::SyntheticRig rig(config);
  std::vector<tlc::PeopleCounts> counts;
  for (int i = 0; i < config.frames; ++i) counts.push_back(rig.render(i).counts);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  tlc::GateConfig gate;
  const auto kept = syn::gateFrames(counts, gate)[tlc::GateDecision::kKept];
  gate.skip_frames = 0;
  const auto equal = syn::gateFrames(counts, gate)[tlc::GateDecision::kKept];
  std::printf("default: %d frames, %llu equal 1..3, %llu kept pairs, %zu people, %.1f s\n", config.frames,
              static_cast<unsigned long long>(equal), static_cast<unsigned long long>(kept),
              rig.scene().people().size(), seconds);
  EXPECT_GE(kept, 55u);
  EXPECT_LE(kept, 95u);
}

// The rig predicts the consumer: the same frames offered to the core ingest path (DatasetBuilder)
// get the same counts and the same number of kept pairs as the rig's gateFrames says.
TEST(SyntheticRig, CountsAgreeWithTheIngestPath) {
  for (const syn::MaskStyle style : {syn::MaskStyle::kIds, syn::MaskStyle::kBinary}) {
    syn::SyntheticConfig config = smallConfig("fieldsafe", 150);
    config.noise = syn::NoiseConfig::realistic();
    config.mask_style = style;
    const syn::SyntheticRig rig(config);
    tlc::DatasetBuilder builder(config.rig.camera, tlc::GateConfig{});
    std::vector<tlc::PeopleCounts> counts;
    for (int i = 0; i < config.frames; ++i) {
      syn::SyntheticFrame frame = rig.render(i);
      counts.push_back(frame.counts);
      const tlc::OfferOutcome outcome = builder.offer([&] {
        tlc::Frame f;
        f.mask = frame.mask;
        f.points = frame.cluster_points;
        f.labels = frame.cluster_labels;
        return f;
      });
      if (outcome.decision == tlc::GateDecision::kSkipped) continue;
      EXPECT_EQ(outcome.mask_people, frame.counts.mask_people) << "frame " << i;
      EXPECT_EQ(outcome.cluster_people, frame.counts.cluster_people) << "frame " << i;
    }
    const tlc::RejectionCounts predicted = syn::gateFrames(counts, tlc::GateConfig{});
    EXPECT_EQ(predicted.by_decision, builder.counts().by_decision);
    EXPECT_GT(builder.pairs().size(), 5u);
  }
}

// A person seen on both sides of a thin post in front of them: one id in the mask but several
// 8-connected regions (arms and torso slivers). In a binary mask the consumer counts two people; so must the rig.
TEST(SyntheticRig, APersonSplitByAPostCountsAsTheConsumerCountsIt) {
  syn::SyntheticConfig config = smallConfig("fieldsafe", 1);
  config.mask_style = syn::MaskStyle::kBinary;
  syn::SyntheticRig rig(config);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translate(Eigen::Vector3d(0, 0, rig.groundZ()));
  // The camera sits ~0.44 m left of the LiDAR: put the post on the camera's line of sight.
  const Eigen::Vector3d camera = -config.rig.truth.rotationMatrix().transpose() * config.rig.truth.translation;
  const Eigen::Vector2d person_xy(10.0, camera.y());
  syn::WorldObject post;
  post.solid = syn::makePost(Eigen::Vector2d(5.0, camera.y() / 2.0 + person_xy.y() / 2.0), 2.5, 0.08).transformed(T);
  post.clutter_id = 1;
  const std::vector<syn::WorldObject> objects{personAt(rig, person_xy.x(), person_xy.y(), 1), post};
  const syn::SyntheticFrame frame = rig.renderSnapshot(objects, 0, 1.6e9);
  ASSERT_GT(cv::countNonZero(frame.mask), 100);
  EXPECT_EQ(frame.counts.mask_people, tlc::countMaskPeople(frame.mask));
  EXPECT_GE(frame.counts.mask_people, 2);  // one person, several regions: the consumer's count
  EXPECT_EQ(frame.counts.cluster_people, 1);
}

TEST(SyntheticRig, NoiseOptionsChangeWhatTheyShould) {
  syn::SyntheticConfig config = smallConfig("fieldsafe", 60);
  syn::SyntheticRig clean(config);
  config.noise.range_sigma_m = 0.05;
  config.noise.mask_edge_px = 3;
  config.mask_style = syn::MaskStyle::kBinary;
  config.image_depth = syn::ImageDepth::kMono16;
  syn::SyntheticRig noisy(config);
  int compared = 0;
  for (int i = 0; i < 60; i += 3) {
    const syn::SyntheticFrame a = clean.render(i), b = noisy.render(i);
    EXPECT_EQ(b.image.type(), CV_16UC1);
    double max_v = 0;
    cv::minMaxLoc(b.mask, nullptr, &max_v);
    if (cv::countNonZero(b.mask) > 0) EXPECT_EQ(max_v, 255.0);
    if (a.cluster_points.size() == b.cluster_points.size() && !a.cluster_points.empty()) {
      double diff = 0;
      for (std::size_t k = 0; k < a.cluster_points.size(); ++k) diff += (a.cluster_points[k] - b.cluster_points[k]).norm();
      EXPECT_GT(diff / a.cluster_points.size(), 0.01);
      EXPECT_LT(diff / a.cluster_points.size(), 0.1);
      ++compared;
    }
  }
  EXPECT_GT(compared, 0);
}

// Grown masks only add pixels, shrunk ones only remove them; both ways does either, from the same
// draws as before the option existed (the realistic drives are the same bags).
TEST(SyntheticRig, MaskEdgesMoveTheWayAsked) {
  cv::Mat ids(120, 160, CV_16UC1, cv::Scalar(0));
  for (int id = 1; id <= 6; ++id) {
    cv::ellipse(ids, cv::Point(20 + 24 * (id - 1), 60), cv::Size(8, 30), 0, 0, 360, cv::Scalar(id), cv::FILLED);
  }
  const int before = cv::countNonZero(ids);
  int grown_removed = 0, shrunk_added = 0, both_grew = 0, both_shrank = 0;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    for (const syn::MaskEdgeSign sign : {syn::MaskEdgeSign::kGrow, syn::MaskEdgeSign::kShrink, syn::MaskEdgeSign::kBoth}) {
      cv::Mat m = ids.clone();
      std::mt19937_64 rng(seed);
      syn::perturbMaskEdges(m, 2, rng, sign);
      for (int id = 1; id <= 6; ++id) {
        const int was = cv::countNonZero(ids == id), now = cv::countNonZero(m == id);
        const cv::Mat lost = (ids == id) & (m != id), gained = (m == id) & (ids != id);
        if (sign == syn::MaskEdgeSign::kGrow) grown_removed += cv::countNonZero(lost);
        if (sign == syn::MaskEdgeSign::kShrink) shrunk_added += cv::countNonZero(gained);
        if (sign == syn::MaskEdgeSign::kBoth) {
          both_grew += now > was;
          both_shrank += now < was;
        }
      }
    }
  }
  EXPECT_GT(before, 0);
  EXPECT_EQ(grown_removed, 0);
  EXPECT_EQ(shrunk_added, 0);
  EXPECT_GT(both_grew, 0);
  EXPECT_GT(both_shrank, 0);
  // The default is both ways, drawn as before.
  cv::Mat a = ids.clone(), b = ids.clone();
  std::mt19937_64 ra(7), rb(7);
  syn::perturbMaskEdges(a, 2, ra);
  syn::perturbMaskEdges(b, 2, rb, syn::MaskEdgeSign::kBoth);
  EXPECT_EQ(cv::countNonZero(a != b), 0);
  EXPECT_EQ(syn::maskEdgeSignByName("shrink"), syn::MaskEdgeSign::kShrink);
  EXPECT_STREQ(syn::toString(syn::MaskEdgeSign::kGrow), "grow");
  EXPECT_THROW(syn::maskEdgeSignByName("inward"), std::invalid_argument);
}

// An erosion splits into the thin parts it loses and the outline it moves in (issue 24's two
// opposite leans): the two parts take disjoint pixels that together are the erosion's.
TEST(SyntheticRig, ErosionPartsSplitTheErosion) {
  cv::Mat ids(80, 80, CV_8UC1, cv::Scalar(0));
  ids(cv::Rect(20, 10, 30, 30)).setTo(1);  // a body
  ids(cv::Rect(34, 40, 2, 25)).setTo(1);   // a leg 2 px wide: narrower than any erosion's kernel
  const cv::Point edge(35, 10), leg(34, 55);  // the body's top edge, in the middle; a leg pixel
  int eroded = 0;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    cv::Mat all = ids.clone(), thin = ids.clone(), outline = ids.clone();
    std::mt19937_64 ra(seed), rt(seed), ro(seed);
    syn::perturbMaskEdges(all, 2, ra, syn::MaskEdgeSign::kShrink, syn::MaskErosionPart::kAll);
    syn::perturbMaskEdges(thin, 2, rt, syn::MaskEdgeSign::kShrink, syn::MaskErosionPart::kThin);
    syn::perturbMaskEdges(outline, 2, ro, syn::MaskEdgeSign::kShrink, syn::MaskErosionPart::kOutline);
    const cv::Mat lost_all = (ids != 0) & (all == 0), lost_thin = (ids != 0) & (thin == 0),
                  lost_outline = (ids != 0) & (outline == 0);
    EXPECT_EQ(cv::countNonZero(lost_thin & lost_outline), 0) << "seed " << seed;
    EXPECT_EQ(cv::countNonZero((lost_thin | lost_outline) != lost_all), 0) << "seed " << seed;
    if (all.at<std::uint8_t>(edge) != 0) continue;  // this seed drew no erosion
    ++eroded;
    EXPECT_EQ(all.at<std::uint8_t>(leg), 0);
    EXPECT_EQ(thin.at<std::uint8_t>(leg), 0);          // the leg is lost...
    EXPECT_NE(thin.at<std::uint8_t>(edge), 0);         // ...the body's outline stays
    EXPECT_NE(outline.at<std::uint8_t>(leg), 0);       // the leg stays...
    EXPECT_EQ(outline.at<std::uint8_t>(edge), 0);      // ...the outline moves in
  }
  EXPECT_GT(eroded, 0);
  EXPECT_EQ(syn::maskErosionPartByName("thin"), syn::MaskErosionPart::kThin);
  EXPECT_STREQ(syn::toString(syn::MaskErosionPart::kOutline), "outline");
  EXPECT_STREQ(syn::toString(syn::MaskErosionPart::kAll), "all");
  EXPECT_THROW(syn::maskErosionPartByName("legs"), std::invalid_argument);
}

TEST(SyntheticRig, PresetsAndBadConfigs) {
  EXPECT_THROW(syn::rigByName("kitti"), std::invalid_argument);
  EXPECT_THROW(syn::NoiseConfig::preset("noisy"), std::invalid_argument);
  const syn::NoiseConfig r = syn::NoiseConfig::realistic();
  EXPECT_EQ(r.mask_edge_px, 2);
  EXPECT_DOUBLE_EQ(r.range_sigma_m, 0.02);
  syn::SyntheticConfig config;
  config.frames = 0;
  EXPECT_THROW(syn::SyntheticRig{config}, std::invalid_argument);
  config.frames = 10;
  config.noise.miss_rate = 1.5;
  EXPECT_THROW(syn::SyntheticRig{config}, std::invalid_argument);
  const auto kept = [](const std::vector<std::pair<int, int>>& frames, int skip) {
    std::vector<tlc::PeopleCounts> counts;
    for (const auto& f : frames) counts.push_back({f.first, f.second, 10});
    tlc::GateConfig gate;
    gate.skip_frames = skip;
    return syn::gateFrames(counts, gate)[tlc::GateDecision::kKept];
  };
  EXPECT_EQ(kept({{1, 1}, {1, 1}, {1, 1}, {1, 1}, {1, 1}, {2, 2}, {0, 0}}, 3), 2u);
  EXPECT_EQ(kept({{1, 1}, {4, 4}, {2, 1}}, 0), 1u);
  // A cluster below min_points_per_cluster rejects the frame, as in the ingest path.
  EXPECT_EQ(syn::gateFrames({{1, 1, 2}}, tlc::GateConfig{})[tlc::GateDecision::kSmallCluster], 1u);
}

// Raw drives carry warm confounders (issue 7): parked vehicles (a cool body, an engine hotter
// than the body band) and animals at body temperature, beside the path, seen within the drive;
// they come from their own random stream, so the people are the same as without them.
TEST(SyntheticRig, RawDrivesHaveParkedVehiclesAndAnimalsBesideTheSamePeople) {
  syn::SyntheticConfig ideal = smallConfig("fieldsafe", 600);
  syn::SyntheticConfig raw = ideal;
  raw.raw = true;
  const syn::SyntheticRig ideal_rig(ideal), raw_rig(raw);
  std::set<int> confounders_seen;
  int engines = 0, animals = 0;
  for (int i = 0; i < 600; i += 20) {
    const auto with = raw_rig.snapshot(i), without = ideal_rig.snapshot(i);
    int people_with = 0, people_without = 0;
    for (const auto& o : with) people_with += o.isPerson() ? 1 : 0;
    for (const auto& o : without) people_without += o.isPerson() ? 1 : 0;
    EXPECT_EQ(people_with, people_without) << "frame " << i;
    for (const auto& o : without) EXPECT_LT(o.clutter_id, 500) << "a confounder in an ideal drive";
    for (const auto& o : with) {
      if (o.clutter_id < 500) continue;
      // Close enough to be seen: within 30 m of the LiDAR.
      if (o.solid.boundingCentre().head<2>().norm() > 30.0) continue;
      if (confounders_seen.insert(o.clutter_id).second) {
        engines += o.grey_level > 255 ? 1 : 0;                        // hotter than any person
        animals += (o.grey_level >= 185 && o.grey_level <= 215) ? 1 : 0;  // in the body band
      }
    }
  }
  EXPECT_GE(engines, 1);
  EXPECT_GE(animals, 1);
}
