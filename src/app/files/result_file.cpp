// The YAML result file of INTERFACE.md and a reader for result / truth files.

#include "thermal_lidar_calibration/app/files/result_file.hpp"
#include "thermal_lidar_calibration/app/report/quality_output.hpp"
#include "thermal_lidar_calibration/app/files/yaml_file.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <stdexcept>

namespace thermal_lidar_calibration {
namespace {

std::string utcNow() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buf[32];
  std::strftime(buf, sizeof(buf), "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

std::string paramValue(const CoreParameters& p, const std::string& key) {
  for (const auto& kv : describeCoreParameters(p)) {
    if (kv.first == key) return kv.second;
  }
  return "";
}

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw std::invalid_argument("extrinsic file " + path + ": " + what);
}

std::vector<double> readNumbers(const YAML::Node& node, const std::string& key,
                                const std::string& path) {
  std::vector<double> values;
  const auto add = [&](const YAML::Node& n) {
    if (n.IsSequence()) {
      for (const auto& m : n) values.push_back(m.as<double>());
    } else {
      values.push_back(n.as<double>());
    }
  };
  try {
    if (node.IsMap() && node["data"]) {
      add(node["data"]);
    } else if (node.IsSequence()) {
      for (const auto& n : node) add(n);  // flat list or list of rows
    } else {
      fail(path, "'" + key + "' is not a list of numbers");
    }
  } catch (const YAML::Exception&) {
    fail(path, "'" + key + "' holds a non-number");
  }
  for (double v : values) {
    if (!std::isfinite(v)) fail(path, "'" + key + "' holds a non-finite number");
  }
  return values;
}

}  // namespace

void emitVector(YAML::Emitter& out, const std::string& key, const double* v, int n) {
  out << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (int i = 0; i < n; ++i) out << v[i];
  out << YAML::EndSeq;
}

void emitExtrinsic(YAML::Emitter& out, const Extrinsic& e) {
  emitVector(out, "rotation_vector", e.rotation_vector.data(), 3);
  emitVector(out, "translation", e.translation.data(), 3);
  const Eigen::Matrix3d R = e.rotationMatrix();
  double r[9];
  for (int i = 0; i < 9; ++i) r[i] = R(i / 3, i % 3);
  emitVector(out, "rotation_matrix", r, 9);
  const Eigen::Quaterniond q = e.quaternion();
  const double xyzw[4] = {q.x(), q.y(), q.z(), q.w()};
  emitVector(out, "quaternion_xyzw", xyzw, 4);
}

namespace {

// Issue 23: how many pairs each rule made, and how the association went.
void emitPairing(YAML::Emitter& out, const PairingSummary& p) {
  out << YAML::Key << "pairs_by_rule" << YAML::Value << YAML::Flow << YAML::BeginMap;
  out << YAML::Key << "counts" << YAML::Value << p.counts;
  out << YAML::Key << "association" << YAML::Value << p.association << YAML::EndMap;
  out << YAML::Key << "association" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "pairing" << YAML::Value << toString(p.mode);
  out << YAML::Key << "candidate_frames" << YAML::Value << p.candidates;
  out << YAML::Key << "rounds" << YAML::Value << p.rounds;
  out << YAML::Key << "converged" << YAML::Value << p.converged;
  out << YAML::Key << "skipped_frames" << YAML::Value << p.skipped_frames;
  out << YAML::Key << "final_round" << YAML::Value << p.final_round;
  out << YAML::Key << "final_round_pairs" << YAML::Value << p.final_round_pairs;
  out << YAML::Key << "initial_extrinsic_used" << YAML::Value << p.initial_used;
  if (!p.note.empty()) out << YAML::Key << "note" << YAML::Value << p.note;
  out << YAML::EndMap;
}

// Issue 21: the camera's time offset the extrinsic goes with (0 and none: timing ignored).
void emitTiming(YAML::Emitter& out, const CalibrationResult& result) {
  out << YAML::Key << "time_offset_s" << YAML::Value << result.time_offset_s;
  out << YAML::Key << "time_offset_mode" << YAML::Value << toString(result.time_offset_mode);
  if (!result.time_offset_note.empty()) {
    out << YAML::Key << "time_offset_note" << YAML::Value << result.time_offset_note;
  }
  out << YAML::Key << "loss_without_timing" << YAML::Value << result.loss_without_timing;
  out << YAML::Key << "pairs_with_motion" << YAML::Value << result.pairs_with_motion;
  if (!result.time_offset_profile_s.empty()) {
    out << YAML::Key << "time_offset_profile" << YAML::Value << YAML::BeginMap;
    out << YAML::Key << "offsets_s" << YAML::Value << YAML::Flow << YAML::BeginSeq;
    for (std::size_t i = 0; i < result.time_offset_profile_s.size(); ++i) {
      if (std::isfinite(result.time_offset_profile_loss[i])) out << result.time_offset_profile_s[i];
    }
    out << YAML::EndSeq << YAML::Key << "losses_px" << YAML::Value << YAML::Flow << YAML::BeginSeq;
    for (double loss : result.time_offset_profile_loss) {
      if (std::isfinite(loss)) out << loss;
    }
    out << YAML::EndSeq << YAML::Key << "pairs" << YAML::Value << result.time_offset_profile_pairs << YAML::EndMap;
  }
}

// How the fit was made: Algorithm 1's or 2's result before refinement, the settings that decide
// it, the run's cost, and the truth it is compared with.
void emitRun(YAML::Emitter& out, const CalibrationResult& result, const ResultContext& context) {
  out << YAML::Key << "evolution" << YAML::Value << YAML::BeginMap;
  emitExtrinsic(out, result.evolution_extrinsic);
  out << YAML::Key << "loss" << YAML::Value << result.evolution_loss;
  out << YAML::Key << "outlier_fits_accepted" << YAML::Value << result.outlier_fits_accepted;
  out << YAML::Key << "full_length" << YAML::Value << result.evolution_full_length;
  out << YAML::EndMap;
  if (result.ring_alias_tried > 0 || result.ring_spacing_rad > 0.0) {
    out << YAML::Key << "ring_alias" << YAML::Value << YAML::Flow << YAML::BeginMap;
    out << YAML::Key << "spacing_deg" << YAML::Value << result.ring_spacing_rad * 180.0 / M_PI;
    out << YAML::Key << "starts_refined" << YAML::Value << result.ring_alias_tried;
    out << YAML::Key << "turn_kept" << YAML::Value << result.ring_alias_turn;
    out << YAML::EndMap;
  }
  // The rings' ends the refinement read against their people's own outlines (ring_ends.hpp).
  if (result.ring_ends > 0) out << YAML::Key << "ring_ends" << YAML::Value << result.ring_ends;
  // Whether the vertical centring (vertical_centring.hpp) moved the estimate, how far, and why not.
  const VerticalCentringOutcome& centring = result.vertical_centring;
  if (centring.ran) {
    out << YAML::Key << "vertical_centring" << YAML::Value << YAML::Flow << YAML::BeginMap;
    out << YAML::Key << "applied" << YAML::Value << centring.applied;
    if (!centring.applied) out << YAML::Key << "skipped_because" << YAML::Value << centring.skipped_because;
    out << YAML::Key << "moved_px" << YAML::Value << YAML::Flow << YAML::BeginSeq << centring.shift_rotation_px
        << centring.shift_translation_px << centring.shift_roll_px << YAML::EndSeq;
    out << YAML::Key << "fitting_pairs" << YAML::Value << centring.fitting.size();
    out << YAML::EndMap;
  }

  out << YAML::Key << "algorithm" << YAML::Value
      << (context.parameters.calibration.algorithm == Algorithm::kPlain ? 1 : 2);
  out << YAML::Key << "refine" << YAML::Value << paramValue(context.parameters, "refine");
  out << YAML::Key << "seed" << YAML::Value << context.parameters.calibration.seed;
  out << YAML::Key << "run_time_s" << YAML::Value << result.seconds;
  out << YAML::Key << "evaluations" << YAML::Value << result.evaluations;
  out << YAML::Key << "points_projected" << YAML::Value << result.points_projected;
  out << YAML::Key << "source" << YAML::Value << context.source;
  out << YAML::Key << "created" << YAML::Value << utcNow();
  if (context.truth) {
    const TruthComparison& t = *context.truth;
    out << YAML::Key << "truth" << YAML::Value << YAML::BeginMap;
    out << YAML::Key << "file" << YAML::Value << t.truth_file;
    out << YAML::Key << "rotation_error_deg" << YAML::Value << t.rotation_error_rad * 180.0 / M_PI;
    out << YAML::Key << "translation_error_m" << YAML::Value << t.translation_error_m;
    out << YAML::Key << "loss" << YAML::Value << t.truth_loss;
    out << YAML::EndMap;
  }
}

// Each pair's stamp, loss and inlier flag, in the order the pairs were kept.
void emitPairs(YAML::Emitter& out, const CalibrationResult& result, const ResultContext& context) {
  out << YAML::Key << "pairs" << YAML::Value << YAML::BeginSeq;
  const std::size_t n = std::max(result.pair_losses.size(), result.inliers.size());
  for (std::size_t i = 0; i < n; ++i) {
    out << YAML::Flow << YAML::BeginMap;
    // A stamp since the epoch has 10 digits before the point: the file's 12 significant digits
    // would round it to 10 ms, more than a camera frame's exposure; 17 keep it to the microsecond.
    out << YAML::Key << "stamp" << YAML::Value << YAML::DoublePrecision(17)
        << (i < context.pair_stamps_s.size() ? context.pair_stamps_s[i] : 0.0);
    out << YAML::Key << "loss" << YAML::Value
        << (i < result.pair_losses.size() ? result.pair_losses[i] : 0.0);
    out << YAML::Key << "inlier" << YAML::Value
        << (i < result.inliers.size() ? static_cast<bool>(result.inliers[i]) : true);
    if (i < context.pair_rules.size()) {
      out << YAML::Key << "rule" << YAML::Value
          << (context.pair_rules[i] == PairRule::kAssociation ? "association" : "counts");
    }
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;
}

// Written next to the target and renamed, so a reader never sees half a file.
void writeFileAtomically(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream file(tmp);
    if (!file) {
      throw std::runtime_error("cannot write result file " + path + ": " + std::strerror(errno));
    }
    file << "# thermal_lidar_calibration result: p_camera = R * p_lidar + t (metres, radians)\n";
    file << text << "\n";
    file.close();
    if (!file) {
      std::remove(tmp.c_str());
      throw std::runtime_error("cannot write result file " + path + ": write failed");
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    std::remove(tmp.c_str());
    throw std::runtime_error("cannot write result file " + path + ": " + reason);
  }
}

}  // namespace

void writeResultFile(const std::string& path, const CalibrationResult& result,
                     const ResultContext& context) {
  YAML::Emitter out;
  out.SetDoublePrecision(12);
  out << YAML::BeginMap;
  out << YAML::Key << "lidar_frame" << YAML::Value << context.lidar_frame;
  out << YAML::Key << "camera_frame" << YAML::Value << context.camera_frame;
  emitExtrinsic(out, result.extrinsic);
  out << YAML::Key << "loss" << YAML::Value << result.loss;
  out << YAML::Key << "pairs_used" << YAML::Value << result.pairs_used;
  out << YAML::Key << "pairs_collected" << YAML::Value << result.pairs_collected;
  if (context.pairing) emitPairing(out, *context.pairing);
  out << YAML::Key << "loss_bilinear" << YAML::Value << result.loss_bilinear;
  out << YAML::Key << "stopped_early" << YAML::Value << result.stopped;
  emitTiming(out, result);
  emitRun(out, result, context);
  if (context.quality) emitQuality(out, *context.quality);
  emitPairs(out, result, context);
  out << YAML::Key << "parameters" << YAML::Value << YAML::BeginMap;
  for (const auto& kv : describeCoreParameters(context.parameters)) {
    out << YAML::Key << kv.first << YAML::Value << kv.second;
  }
  out << YAML::EndMap;
  out << YAML::EndMap;
  if (!out.good()) {
    throw std::runtime_error("cannot write result file " + path + ": " + out.GetLastError());
  }
  writeFileAtomically(path, out.c_str());
}

std::optional<double> readTimeOffset(const std::string& path, bool point_times) {
  const YAML::Node root = loadYamlFile(path, "extrinsic file");
  if (!root.IsMap()) return std::nullopt;
  const char* key = !point_times && root["time_offset_at_scan_stamp_s"] ? "time_offset_at_scan_stamp_s"
                                                                        : "time_offset_s";
  if (!root[key]) return std::nullopt;
  double seconds = 0.0;
  try {
    seconds = root[key].as<double>();
  } catch (const YAML::Exception&) {
    fail(path, std::string("'") + key + "' must be one number (seconds)");
  }
  if (!std::isfinite(seconds)) fail(path, std::string("'") + key + "' is not finite");
  return seconds;
}

std::optional<double> readAppliedTimeOffset(const std::string& path) {
  const YAML::Node root = loadYamlFile(path, "extrinsic file");
  if (root.IsMap() && root["time_offset_mode"] && root["time_offset_mode"].IsScalar() &&
      root["time_offset_mode"].as<std::string>() == "none") {
    return std::nullopt;
  }
  return readTimeOffset(path, true);
}

void checkExtrinsicFile(const std::string& path, const Extrinsic& expected) {
  const Extrinsic stored = readExtrinsicFile(path);
  if ((stored.rotation_vector - expected.rotation_vector).norm() > 1e-9 ||
      (stored.translation - expected.translation).norm() > 1e-9) {
    throw std::runtime_error(path + " does not hold the extrinsic after writing");
  }
}

Extrinsic readExtrinsicFile(const std::string& path) {
  const YAML::Node root = loadYamlFile(path, "extrinsic file");
  if (!root.IsMap()) fail(path, "is not a YAML map with rotation_vector and translation");
  if (!root["translation"]) fail(path, "has no 'translation' [tx, ty, tz] (metres)");
  const std::vector<double> t = readNumbers(root["translation"], "translation", path);
  if (t.size() != 3) fail(path, "'translation' needs 3 values, has " + std::to_string(t.size()));
  const Eigen::Vector3d translation(t[0], t[1], t[2]);
  if (root["rotation_vector"]) {
    const std::vector<double> r = readNumbers(root["rotation_vector"], "rotation_vector", path);
    if (r.size() != 3) {
      fail(path, "'rotation_vector' needs 3 values, has " + std::to_string(r.size()));
    }
    Extrinsic e;
    e.rotation_vector = Eigen::Vector3d(r[0], r[1], r[2]);
    e.translation = translation;
    return e;
  }
  if (root["rotation_matrix"]) {
    const std::vector<double> m = readNumbers(root["rotation_matrix"], "rotation_matrix", path);
    if (m.size() != 9) {
      fail(path, "'rotation_matrix' needs 9 values (row-major), has " + std::to_string(m.size()));
    }
    Eigen::Matrix3d R;
    for (int i = 0; i < 9; ++i) R(i / 3, i % 3) = m[i];
    if ((R.transpose() * R - Eigen::Matrix3d::Identity()).norm() > 1e-3 || R.determinant() < 0) {
      fail(path, "'rotation_matrix' is not a rotation (R^T R != I or det < 0)");
    }
    return Extrinsic::fromRotationMatrix(R, translation);
  }
  fail(path, "has neither 'rotation_vector' nor 'rotation_matrix'");
}

}  // namespace thermal_lidar_calibration
