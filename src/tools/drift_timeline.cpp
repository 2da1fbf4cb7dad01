#include "thermal_lidar_calibration/tools/drift_timeline.hpp"

#include "thermal_lidar_calibration/app/report/quality_output.hpp"
#include "thermal_lidar_calibration/app/files/result_file.hpp"

#include <opencv2/imgproc.hpp>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace thermal_lidar_calibration {

DriftTimeline watchDrift(const CameraModel& camera, const std::vector<CalibrationPair>& stream,
                         const Extrinsic& reference, const DriftConfig& drift,
                         const CalibrationConfig& calibration,
                         const std::function<bool(std::size_t, std::size_t)>& progress,
                         std::optional<double> time_offset_s,
                         const std::optional<AssociationPairing>& association) {
  DriftMonitor monitor(camera, reference, drift, calibration, time_offset_s);
  if (association) monitor.pairByAssociation(*association);
  DriftTimeline timeline;
  timeline.reference = reference;
  for (std::size_t i = 0; i < stream.size(); ++i) {
    if (auto record = monitor.add(stream[i])) timeline.records.push_back(*record);
    if (progress && !progress(i + 1, stream.size())) break;
  }
  timeline.association_pairs = monitor.associationPairs();
  timeline.candidates = monitor.candidatesOffered();
  timeline.candidate = monitor.candidate();
  timeline.state = monitor.state();
  timeline.first_warn_stamp_s = monitor.firstWarnStamp();
  timeline.first_error_stamp_s = monitor.firstErrorStamp();
  timeline.pairs = monitor.pairsSeen();
  timeline.seconds = monitor.secondsInTests();
  timeline.time_offset_s = monitor.timeOffset();
  timeline.timing_state = monitor.timingState();
  timeline.timing_change_s = monitor.timingChange();
  return timeline;
}

void writeDriftCsv(const std::string& path, const DriftTimeline& timeline) {
  std::ofstream out(path);
  // The INTERFACE's columns come first; then pairs_seen (kept pairs given to the watch so far)
  // and each test's evidence, so a user can see which part of the test held or failed.
  // Then the offset test's evidence: the window's image offset across and down the image
  // against the reference, px, its p-values and the pairs in it.
  out << "stamp,pairs_in_window,state,rotation_change_deg,translation_change_cm,loss_reference,"
         "loss_fit,pairs_seen,p_value,held_out_pairs,image_shift_px,pairs_used,changed,"
         "offset_x_px,offset_y_px,offset_p_value_x,offset_p_value_y,offset_pairs,timing_state,"
         "timing_change_ms\n";
  char row[480];
  for (const DriftRecord& r : timeline.records) {
    std::snprintf(row, sizeof(row),
                  "%.3f,%zu,%s,%.4f,%.3f,%.5f,%.5f,%llu,%.3g,%zu,%.3f,%zu,%d,%.3f,%.3f,%.3g,%.3g,%zu,%s,%.1f\n",
                  r.stamp_s, r.test.pairs_in_window, toString(r.state), r.test.change.angle_deg,
                  r.test.change.distance_cm, r.test.loss_reference, r.test.loss_fit,
                  static_cast<unsigned long long>(r.pairs_seen), r.test.p_value,
                  r.test.held_out_pairs, r.test.image_shift_px, r.test.pairs_used,
                  r.test.changed() ? 1 : 0, r.test.offset_px.x(), r.test.offset_px.y(),
                  r.test.offset_p_value.x(), r.test.offset_p_value.y(), r.test.offset_pairs,
                  toString(r.timing_state), r.timing_change_s ? 1000.0 * *r.timing_change_s : 0.0);
    out << row;
  }
  out.close();
  if (!out) throw std::runtime_error("cannot write the drift timeline " + path);
}

void writeDriftResult(const std::string& path, const DriftTimeline& timeline,
                      const std::string& lidar_frame, const std::string& camera_frame,
                      const std::string& reference_file) {
  YAML::Emitter out;
  out.SetDoublePrecision(12);
  out << YAML::BeginMap;
  out << YAML::Key << "lidar_frame" << YAML::Value << lidar_frame;
  out << YAML::Key << "camera_frame" << YAML::Value << camera_frame;
  // The latest fit: the new extrinsic after a confirmed change, else the last window's.
  const DriftRecord* last = timeline.records.empty() ? nullptr : &timeline.records.back();
  if (timeline.candidate) {
    emitExtrinsic(out, timeline.candidate->extrinsic);
    out << YAML::Key << "loss" << YAML::Value << timeline.candidate->loss_fit;
    out << YAML::Key << "pairs_used" << YAML::Value << timeline.candidate->pairs_used;
    out << YAML::Key << "pairs_collected" << YAML::Value << timeline.candidate->pairs;
  } else if (last) {
    emitExtrinsic(out, last->test.fit);
    out << YAML::Key << "loss" << YAML::Value << last->test.loss_fit;
    out << YAML::Key << "pairs_used" << YAML::Value << last->test.pairs_used;
    out << YAML::Key << "pairs_collected" << YAML::Value << last->test.pairs_in_window;
  } else {
    emitExtrinsic(out, timeline.reference);
    out << YAML::Key << "loss" << YAML::Value << YAML::Null;
    out << YAML::Key << "pairs_used" << YAML::Value << 0;
    out << YAML::Key << "pairs_collected" << YAML::Value << timeline.pairs;
  }
  const auto stamp = [&](const std::optional<double>& s) {
    if (s) {
      out << *s;
    } else {
      out << YAML::Null;
    }
  };
  out << YAML::Key << "drift" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "state" << YAML::Value << toString(timeline.state);
  out << YAML::Key << "first_warn_stamp" << YAML::Value;
  stamp(timeline.first_warn_stamp_s);
  out << YAML::Key << "first_error_stamp" << YAML::Value;
  stamp(timeline.first_error_stamp_s);
  const DriftChange change = timeline.candidate ? timeline.candidate->change
                             : last             ? last->test.change
                                                : DriftChange{};
  out << YAML::Key << "rotation_change_deg" << YAML::Value << change.angle_deg;
  const double t[3] = {change.translation_cm.x(), change.translation_cm.y(), change.translation_cm.z()};
  emitVector(out, "translation_change_cm", t, 3);
  const double r[3] = {change.rotation_deg.x(), change.rotation_deg.y(), change.rotation_deg.z()};
  emitVector(out, "rotation_change_axes_deg", r, 3);
  out << YAML::Key << "reference_file" << YAML::Value << reference_file;
  // Issue 21: timing apart from the extrinsic.
  out << YAML::Key << "time_offset_s" << YAML::Value;
  stamp(timeline.time_offset_s);
  out << YAML::Key << "timing_state" << YAML::Value << toString(timeline.timing_state);
  out << YAML::Key << "time_offset_change_ms" << YAML::Value;
  if (timeline.timing_change_s) {
    out << 1000.0 * *timeline.timing_change_s;
  } else {
    out << YAML::Null;
  }
  out << YAML::Key << "pairs" << YAML::Value << timeline.pairs;
  out << YAML::Key << "pairs_by_rule" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "counts" << YAML::Value << timeline.pairs - timeline.association_pairs;
  out << YAML::Key << "association" << YAML::Value << timeline.association_pairs;
  out << YAML::EndMap;
  out << YAML::Key << "tests" << YAML::Value << timeline.records.size();
  if (timeline.candidate) {
    const DriftCandidate& c = *timeline.candidate;
    out << YAML::Key << "candidate" << YAML::Value << YAML::BeginMap;
    out << YAML::Key << "change_stamp" << YAML::Value << c.change_stamp_s;
    out << YAML::Key << "complete" << YAML::Value << c.complete;
    out << YAML::Key << "loss_reference" << YAML::Value << c.loss_reference;
    out << YAML::Key << "loss_fit" << YAML::Value << c.loss_fit;
    out << YAML::Key << "p_value" << YAML::Value << c.p_value;
    out << YAML::Key << "model" << YAML::Value << toString(c.model);
    out << YAML::Key << "full_p_value" << YAML::Value << c.full_p_value;
    if (c.uncertainty) emitUncertainty(out, *c.uncertainty);
    out << YAML::EndMap;
  }
  out << YAML::EndMap;
  out << YAML::EndMap;
  std::ofstream file(path);
  file << "# thermal_lidar_calibration drift watch: the latest fit and the drift state\n"
       << out.c_str() << "\n";
  file.close();
  if (!file) throw std::runtime_error("cannot write result file " + path);
}

cv::Mat drawDriftPlot(const DriftTimeline& timeline, int width, int height) {
  cv::Mat img(height, width, CV_8UC3, cv::Scalar(255, 255, 255));
  const int left = 70, right = 20, top = 30, gap = 40, bottom = 40;
  const int panel_h = (height - top - gap - bottom) / 2;
  if (timeline.records.empty()) {
    cv::putText(img, "no drift test ran: fewer kept pairs than monitor_window_pairs", {left, height / 2},
                cv::FONT_HERSHEY_SIMPLEX, 0.6, {0, 0, 0}, 1, cv::LINE_AA);
    return img;
  }
  const double t0 = timeline.records.front().stamp_s, t1 = std::max(t0 + 1e-3, timeline.records.back().stamp_s);
  const auto x_of = [&](double t) { return left + static_cast<int>((t - t0) / (t1 - t0) * (width - left - right)); };
  const cv::Scalar axis_colour[3] = {{40, 40, 220}, {40, 160, 40}, {220, 90, 40}};  // x red, y green, z blue
  for (int panel = 0; panel < 2; ++panel) {
    const int y0 = top + panel * (panel_h + gap);
    double limit = panel == 0 ? 0.5 : 3.0;  // at least the bump sizes fit
    for (const auto& r : timeline.records) {
      const Eigen::Vector3d v = panel == 0 ? r.test.change.rotation_deg : r.test.change.translation_cm;
      limit = std::max(limit, v.cwiseAbs().maxCoeff() * 1.1);
    }
    const auto y_of = [&](double v) { return y0 + panel_h / 2 - static_cast<int>(v / limit * panel_h / 2); };
    // WARN / ERROR shading behind the curves.
    for (std::size_t i = 0; i < timeline.records.size(); ++i) {
      const DriftRecord& r = timeline.records[i];
      if (r.state == DriftState::kOk) continue;
      const double next = i + 1 < timeline.records.size() ? timeline.records[i + 1].stamp_s : t1;
      const cv::Scalar shade = r.state == DriftState::kWarn ? cv::Scalar(170, 220, 255) : cv::Scalar(180, 180, 255);
      cv::rectangle(img, {x_of(r.stamp_s), y0}, {std::max(x_of(r.stamp_s) + 2, x_of(next)), y0 + panel_h}, shade,
                    cv::FILLED);
    }
    cv::rectangle(img, {left, y0}, {width - right, y0 + panel_h}, {0, 0, 0}, 1);
    cv::line(img, {left, y_of(0)}, {width - right, y_of(0)}, {160, 160, 160}, 1);
    for (int k = 0; k < 3; ++k) {
      for (std::size_t i = 1; i < timeline.records.size(); ++i) {
        const auto& a = timeline.records[i - 1].test.change;
        const auto& b = timeline.records[i].test.change;
        const double va = panel == 0 ? a.rotation_deg[k] : a.translation_cm[k];
        const double vb = panel == 0 ? b.rotation_deg[k] : b.translation_cm[k];
        cv::line(img, {x_of(timeline.records[i - 1].stamp_s), y_of(va)}, {x_of(timeline.records[i].stamp_s), y_of(vb)},
                 axis_colour[k], 2, cv::LINE_AA);
      }
    }
    char label[96];
    std::snprintf(label, sizeof(label), panel == 0 ? "rotation change, deg (+-%.2f)" : "translation change, cm (+-%.1f)",
                  limit);
    cv::putText(img, label, {left + 5, y0 - 8}, cv::FONT_HERSHEY_SIMPLEX, 0.5, {0, 0, 0}, 1, cv::LINE_AA);
  }
  char legend[160];
  std::snprintf(legend, sizeof(legend), "camera x red, y green, z blue; WARN orange, ERROR red; %.0f s, %zu tests, final %s",
                t1 - t0, timeline.records.size(), toString(timeline.state));
  cv::putText(img, legend, {left, height - 12}, cv::FONT_HERSHEY_SIMPLEX, 0.5, {0, 0, 0}, 1, cv::LINE_AA);
  return img;
}

}  // namespace thermal_lidar_calibration
