// rostests of pairing by association in calibration_node (issue 23; node_association*.test):
// a drive with realistic noise is played to the node; its result file must count association
// pairs (the frames the count rule did not keep, paired person by person by the same job
// calibrate_bag runs), carry no "not applied" note, and land near the generator's truth.

#include "thermal_lidar_calibration/app/files/result_file.hpp"
#include "thermal_lidar_calibration/core/extrinsic.hpp"

#include "../support/node_observer.hpp"

#include <gtest/gtest.h>
#include <ros/ros.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <iostream>
#include <string>

using thermal_lidar_calibration::Extrinsic;
using namespace node_observer;

TEST(NodeAssociation, PairsByAssociationAndLandsNearTheTruth) {
  ros::NodeHandle pnh("~");
  const std::string truth_file = pnh.param<std::string>("truth_file", "");
  const std::string result_file = pnh.param<std::string>("result_file", "");
  // The player starts paused (node_association.test): its ~paused comes once the drive and its
  // truth file are in place.
  ASSERT_TRUE(waitFor(kHangGuardS, [] { return g_observed.player_paused_pairs.has_value(); }))
      << "the player never paused: " << g_observed.last_status;
  resumePlayer();
  ASSERT_TRUE(waitFor(pnh.param("timeout_s", 240.0), [] { return g_observed.last_status.state_name == "done"; }))
      << "states seen: " << joined(g_observed.states) << "; status: " << g_observed.last_status;
  {
    std::lock_guard<std::mutex> lock(g_observed.mutex);
    EXPECT_GT(g_observed.last_status.association_candidates, 0u) << g_observed.last_status;
  }

  const YAML::Node y = YAML::LoadFile(result_file);
  const int counts = y["pairs_by_rule"]["counts"].as<int>();
  const int association = y["pairs_by_rule"]["association"].as<int>();
  std::cout << "[ node ] pairs by rule: counts " << counts << ", association " << association << " (of "
            << y["association"]["candidate_frames"].as<int>() << " candidate frames)\n";
  EXPECT_GE(counts, 30);
  EXPECT_GT(association, 0);
  EXPECT_EQ(counts + association, y["pairs_collected"].as<int>());
  EXPECT_EQ(y["association"]["pairing"].as<std::string>(), "association");
  EXPECT_GT(y["association"]["candidate_frames"].as<int>(), 0);
  const std::string note = y["association"]["note"] ? y["association"]["note"].as<std::string>() : "";
  EXPECT_EQ(note.find("not applied"), std::string::npos) << note;

  const Extrinsic truth = thermal_lidar_calibration::readExtrinsicFile(truth_file);
  const Extrinsic result = thermal_lidar_calibration::readExtrinsicFile(result_file);
  const double rot_err_deg = thermal_lidar_calibration::rotationErrorRad(result, truth) * 180.0 / M_PI;
  const double trans_err_m = thermal_lidar_calibration::translationErrorM(result, truth);
  std::cout << "[ node ] rotation error " << rot_err_deg << " deg, translation error " << trans_err_m << " m\n";
  EXPECT_LT(rot_err_deg, pnh.param("rotation_tolerance_deg", 0.3));
  EXPECT_LT(trans_err_m, pnh.param("translation_tolerance_m", 0.05));
}

int main(int argc, char** argv) { return runNodeTests(argc, argv, "node_association_test"); }
