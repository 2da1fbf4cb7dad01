// The result file after drift updates: the extrinsic in use and how it came to be.

#include "thermal_lidar_calibration/node/drift_update_file.hpp"

#include "thermal_lidar_calibration/app/report/quality_output.hpp"
#include "thermal_lidar_calibration/app/files/result_file.hpp"

#include <yaml-cpp/yaml.h>

#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace thermal_lidar_calibration {
namespace {

void emitPose(YAML::Emitter& out, const std::string& key, const Extrinsic& e) {
  out << YAML::Key << key << YAML::Value << YAML::BeginMap;
  emitVector(out, "rotation_vector", e.rotation_vector.data(), 3);
  emitVector(out, "translation", e.translation.data(), 3);
  out << YAML::EndMap;
}

}  // namespace

void writeDriftUpdateFile(const std::string& path, const std::string& lidar_frame,
                          const std::string& camera_frame,
                          const std::vector<DriftUpdateEntry>& history) {
  if (history.empty()) throw std::invalid_argument("writeDriftUpdateFile: no update");
  const DriftCandidate& latest = history.back().update.accepted;
  YAML::Emitter out;
  out.SetDoublePrecision(12);
  out << YAML::BeginMap;
  out << YAML::Key << "lidar_frame" << YAML::Value << lidar_frame;
  out << YAML::Key << "camera_frame" << YAML::Value << camera_frame;
  out << YAML::Key << "source" << YAML::Value << "drift_update";
  emitExtrinsic(out, latest.extrinsic);
  out << YAML::Key << "loss" << YAML::Value << latest.loss_fit;
  out << YAML::Key << "pairs_used" << YAML::Value << latest.pairs_used;
  out << YAML::Key << "pairs_collected" << YAML::Value << latest.pairs;
  out << YAML::Key << "drift_updates" << YAML::Value << YAML::BeginSeq;
  for (const DriftUpdateEntry& entry : history) {
    const DriftCandidate& c = entry.update.accepted;
    out << YAML::BeginMap;
    out << YAML::Key << "accepted_by" << YAML::Value << entry.accepted_by;
    out << YAML::Key << "wall_time" << YAML::Value << entry.wall_time_s;
    out << YAML::Key << "change_stamp" << YAML::Value << c.change_stamp_s;
    out << YAML::Key << "confirmed_stamp" << YAML::Value;
    if (c.first_error_stamp_s) {
      out << *c.first_error_stamp_s;
    } else {
      out << YAML::Null;
    }
    emitPose(out, "old", entry.update.old_reference);
    emitPose(out, "new", c.extrinsic);
    out << YAML::Key << "rotation_change_deg" << YAML::Value << c.change.angle_deg;
    emitVector(out, "rotation_change_axes_deg", c.change.rotation_deg.data(), 3);
    emitVector(out, "translation_change_cm", c.change.translation_cm.data(), 3);
    out << YAML::Key << "loss_reference" << YAML::Value << c.loss_reference;
    out << YAML::Key << "loss_fit" << YAML::Value << c.loss_fit;
    out << YAML::Key << "pairs" << YAML::Value << c.pairs;
    out << YAML::Key << "pairs_used" << YAML::Value << c.pairs_used;
    out << YAML::Key << "p_value" << YAML::Value << c.p_value;
    out << YAML::Key << "complete" << YAML::Value << c.complete;
    out << YAML::Key << "model" << YAML::Value << toString(c.model);
    out << YAML::Key << "full_p_value" << YAML::Value << c.full_p_value;
    if (c.uncertainty) emitUncertainty(out, *c.uncertainty);
    out << YAML::EndMap;
  }
  out << YAML::EndSeq << YAML::EndMap;

  const std::string tmp = path + ".tmp";
  {
    std::ofstream file(tmp);
    file << "# thermal_lidar_calibration: extrinsic updated by the drift watch (p_C = R p_L + t)\n"
         << out.c_str() << "\n";
    file.close();
    if (!file || std::rename(tmp.c_str(), path.c_str()) != 0) {
      std::remove(tmp.c_str());
      throw std::runtime_error("cannot write result file " + path);
    }
  }
  checkExtrinsicFile(path, latest.extrinsic);
}

}  // namespace thermal_lidar_calibration
