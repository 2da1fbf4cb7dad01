#include "thermal_lidar_calibration/app/report/quality_output.hpp"

#include "thermal_lidar_calibration/app/files/result_file.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace thermal_lidar_calibration {
namespace {

void emit3(YAML::Emitter& out, const std::string& key, const Eigen::Vector3d& v) {
  const double values[3] = {v.x(), v.y(), v.z()};
  emitVector(out, key, values, 3);
}

std::string format3(const char* format, const Eigen::Vector3d& v) {
  char text[160];
  std::snprintf(text, sizeof(text), format, v.x(), v.y(), v.z());
  return text;
}

}  // namespace

void emitUncertainty(YAML::Emitter& out, const Uncertainty& u) {
  out << YAML::Key << "uncertainty" << YAML::Value << YAML::BeginMap;
  emit3(out, "rotation_deg", u.rotation_deg);
  emit3(out, "translation_cm", u.translation_cm);
  out << YAML::Key << "method" << YAML::Value << "bootstrap";
  out << YAML::Key << "description" << YAML::Value << u.method();
  out << YAML::Key << "confidence" << YAML::Value << u.confidence;
  out << YAML::Key << "resamples" << YAML::Value << u.resamples;
  out << YAML::Key << "block_pairs" << YAML::Value << u.block_pairs;
  out << YAML::Key << "pairs" << YAML::Value << u.pairs;
  out << YAML::Key << "run_time_s" << YAML::Value << u.seconds;
  if (u.timed) {
    out << YAML::Key << "time_offset_ms" << YAML::Value << u.time_offset_ms;
    out << YAML::Key << "time_offset_interval_ms" << YAML::Value << YAML::Flow << YAML::BeginSeq
        << u.time_offset_lower_ms << u.time_offset_upper_ms << YAML::EndSeq;
    emit3(out, "time_translation_correlation", u.time_translation_correlation);
  }
  out << YAML::EndMap;
}

void emitTiming(YAML::Emitter& out, const TimingAssessment& t) {
  out << YAML::Key << "timing" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "pairs_with_motion" << YAML::Value << t.pairs_with_motion;
  out << YAML::Key << "mean_image_speed_px_s" << YAML::Value << t.mean_image_speed_px_s;
  if (std::isfinite(t.resolution_ms)) {
    out << YAML::Key << "resolution_ms" << YAML::Value << t.resolution_ms;
  } else {
    out << YAML::Key << "resolution_ms" << YAML::Value << ".inf";
  }
  out << YAML::Key << "speed_loss_correlation" << YAML::Value << t.speed_loss_correlation;
  if (t.probe_offset_s) {
    out << YAML::Key << "probe_time_offset_s" << YAML::Value << *t.probe_offset_s;
    out << YAML::Key << "probe_loss" << YAML::Value << t.probe_loss;
    out << YAML::Key << "fit_loss" << YAML::Value << t.fit_loss;
  }
  out << YAML::EndMap;
}

void emitQuality(YAML::Emitter& out, const QualityAssessment& q) {
  if (q.uncertainty) emitUncertainty(out, *q.uncertainty);
  const Coverage& c = q.coverage;
  out << YAML::Key << "coverage" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "grid_columns" << YAML::Value << c.grid_columns;
  out << YAML::Key << "grid_rows" << YAML::Value << c.grid_rows;
  out << YAML::Key << "grid_person_pixels" << YAML::Value << YAML::Flow << c.grid_pixels;
  out << YAML::Key << "third_fractions" << YAML::Value << YAML::Flow << YAML::BeginSeq
      << c.thirdFraction(kLeftThird) << c.thirdFraction(kCentreThird) << c.thirdFraction(kRightThird)
      << YAML::EndSeq;
  out << YAML::Key << "pairs" << YAML::Value << c.pairs;
  out << YAML::Key << "people" << YAML::Value << c.people;
  out << YAML::Key << "people_near" << YAML::Value << c.people_near;
  out << YAML::Key << "people_far" << YAML::Value << c.people_far;
  out << YAML::Key << "near_far_split_m" << YAML::Value << c.near_far_split_m;
  out << YAML::Key << "range_m" << YAML::Value << YAML::Flow << YAML::BeginSeq << c.range_min_m
      << c.range_median_m << c.range_max_m << YAML::EndSeq;
  if (c.has_bearing) {
    out << YAML::Key << "bearing_deg" << YAML::Value << YAML::Flow << YAML::BeginSeq
        << c.bearing_min_deg << c.bearing_max_deg << YAML::EndSeq;
  }
  out << YAML::Key << "distinct_positions" << YAML::Value << c.distinct_positions;
  out << YAML::EndMap;
  if (q.timing) emitTiming(out, *q.timing);
  out << YAML::Key << "verdict" << YAML::Value << toString(q.verdict.verdict);
  out << YAML::Key << "verdict_reasons" << YAML::Value << YAML::BeginSeq;
  for (const auto& reason : q.verdict.reasons) out << reason;
  out << YAML::EndSeq;
  if (q.reference) {
    const ReferenceComparison& r = *q.reference;
    out << YAML::Key << "reference" << YAML::Value << YAML::BeginMap;
    out << YAML::Key << "source" << YAML::Value << r.source;
    out << YAML::Key << "origin" << YAML::Value << r.origin;
    out << YAML::Key << "rotation_difference_deg" << YAML::Value << r.difference.angle_deg;
    emit3(out, "rotation_difference_axes_deg", r.difference.rotation_deg);
    emit3(out, "translation_difference_cm", r.difference.translation_cm);
    out << YAML::Key << "loss" << YAML::Value << r.reference_loss;
    out << YAML::Key << "our_loss" << YAML::Value << r.our_loss;
    out << YAML::Key << "pairs" << YAML::Value << r.pairs;
    if (r.within_uncertainty) {
      out << YAML::Key << "within_uncertainty" << YAML::Value << YAML::Flow << YAML::BeginSeq;
      for (bool b : *r.within_uncertainty) out << b;
      out << YAML::EndSeq;
    }
    emitExtrinsic(out, r.reference);
    out << YAML::EndMap;
  }
}

std::string formatHalfWidths(const Uncertainty& u) {
  return format3("+-[%.3f, %.3f, %.3f] deg, ", u.rotation_deg) +
         format3("+-[%.2f, %.2f, %.2f] cm", u.translation_cm);
}

std::string formatQualitySummary(const QualityAssessment& q) {
  std::string s;
  if (q.uncertainty) {
    const Uncertainty& u = *q.uncertainty;
    char percent[16];
    std::snprintf(percent, sizeof(percent), "%.0f", 100.0 * u.confidence);
    s += std::string("  uncertainty      ") + percent + " % intervals (" + u.method() + "):\n";
    s += format3("                   rotation +- [%.3f, %.3f, %.3f] deg about camera x, y, z\n", u.rotation_deg);
    s += format3("                   translation +- [%.2f, %.2f, %.2f] cm along camera x, y, z\n",
                 u.translation_cm);
    if (u.timed) {
      char timing[96];
      std::snprintf(timing, sizeof(timing), "                   time offset +- %.1f ms\n", u.time_offset_ms);
      s += timing;
    }
  }
  const Coverage& c = q.coverage;
  char coverage[256];
  std::snprintf(coverage, sizeof(coverage),
                "  coverage         image thirds %.0f / %.0f / %.0f %% (left / centre / right); people "
                "%zu near, %zu far (split %.0f m), range %.1f-%.1f m; %zu distinct places\n",
                100 * c.thirdFraction(kLeftThird), 100 * c.thirdFraction(kCentreThird),
                100 * c.thirdFraction(kRightThird), c.people_near, c.people_far, c.near_far_split_m,
                c.range_min_m, c.range_max_m, c.distinct_positions);
  s += coverage;
  s += std::string("  verdict          ") + toString(q.verdict.verdict) + "\n";
  for (const auto& reason : q.verdict.reasons) s += "                   - " + reason + "\n";
  if (q.reference) {
    const ReferenceComparison& r = *q.reference;
    char ref[320];
    std::snprintf(ref, sizeof(ref),
                  "  reference        %s: differs by %.3f deg, [%.2f, %.2f, %.2f] cm; its loss %.4f px "
                  "vs ours %.4f px (same %zu pairs)%s\n",
                  r.origin.c_str(), r.difference.angle_deg, r.difference.translation_cm.x(),
                  r.difference.translation_cm.y(), r.difference.translation_cm.z(), r.reference_loss,
                  r.our_loss, r.pairs,
                  !r.within_uncertainty ? ""
                  : std::all_of(r.within_uncertainty->begin(), r.within_uncertainty->end(),
                                [](bool b) { return b; })
                      ? "; within the intervals on every axis"
                      : "; outside the intervals on some axis");
    s += ref;
  }
  return s;
}

}  // namespace thermal_lidar_calibration
