#include "thermal_lidar_calibration/core/verdict.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace thermal_lidar_calibration {
namespace {

void requireOrder(const char* good_key, double good, const char* usable_key, double usable,
                  bool good_is_smaller) {
  if (good_is_smaller ? good > usable : good < usable) {
    std::ostringstream s;
    s << "parameters '" << good_key << "' = " << good << " and '" << usable_key << "' = " << usable
      << ": the good threshold must be " << (good_is_smaller ? "at most" : "at least")
      << " the usable one";
    throw std::invalid_argument(s.str());
  }
}

std::string format(const char* fmt, double a, double b = 0.0, double c = 0.0) {
  char buf[256];
  std::snprintf(buf, sizeof(buf), fmt, a, b, c);
  return buf;
}

struct Finding {
  Verdict level;
  std::string text;
};

const char* kAxis[3] = {"x", "y", "z"};

// The axis with the largest half-width and its value.
std::pair<int, double> widest(const Eigen::Vector3d& half_widths) {
  int k = 0;
  half_widths.maxCoeff(&k);
  return {k, half_widths[k]};
}

void judgeUncertainty(const Uncertainty& u, const VerdictConfig& c, std::vector<Finding>& out) {
  const auto [rk, rot] = widest(u.rotation_deg);
  const auto [tk, trans] = widest(u.translation_cm);
  const auto level = [](double v, double good, double usable) {
    return v <= good ? Verdict::kGood : v <= usable ? Verdict::kUsable : Verdict::kCollectMore;
  };
  const Verdict rot_level = level(rot, c.good_rotation_deg, c.usable_rotation_deg);
  const Verdict trans_level = level(trans, c.good_translation_cm, c.usable_translation_cm);
  if (rot_level != Verdict::kGood) {
    out.push_back({rot_level,
                   std::string("rotation about the camera's ") + kAxis[rk] + " axis is uncertain " +
                       format("by +-%.3f deg (good <= %.3g, usable <= %.3g)", rot,
                              c.good_rotation_deg, c.usable_rotation_deg) +
                       ": collect more pairs with people spread across the image, far ones too"});
  }
  if (trans_level != Verdict::kGood) {
    const std::string advice =
        tk == 2 ? ": collect more pairs with people near the vehicle (along the optical axis "
                  "tilt trades with height; near people pin it)"
                : ": collect more pairs with people near the vehicle and across the image";
    out.push_back({trans_level, std::string("translation along the camera's ") + kAxis[tk] +
                                    " axis is uncertain " +
                                    format("by +-%.2f cm (good <= %.3g, usable <= %.3g)", trans,
                                           c.good_translation_cm, c.usable_translation_cm) +
                                    advice});
  }
}

// Issue 21: timing findings come before the data-volume ones of the same level, so a user whose
// stamps are off is told so rather than to collect more pairs.
void judgeTiming(const TimingAssessment& t, const VerdictConfig& c, std::vector<Finding>& out) {
  const std::string what_to_do =
      ": vary the speed (stop and start), turn while people are in view, or have people walk "
      "across the view; or measure the offset and set time_offset_mode fixed with time_offset_s";
  const bool estimated = t.mode == TimeOffsetMode::kEstimate;
  if (t.asked == TimeOffsetMode::kEstimate && !(t.resolution_ms <= c.good_time_resolution_ms)) {
    const bool hopeless = !(t.resolution_ms <= c.usable_time_offset_ms);
    const std::string resolves =
        std::isfinite(t.resolution_ms)
            ? format("timing: this drive resolves the camera's time offset only to +-%.3g ms (good <= %.3g)",
                     t.resolution_ms, c.good_time_resolution_ms)
            : std::string("timing: this drive cannot tell the camera's time offset at all");
    const std::string consequence =
        estimated ? ", so a late camera and one mounted further along the direction of travel look alike (the "
                    "estimated offset and the translation along the travel are uncertain)"
                  : format(", so it was not estimated (kept at %+.1f ms): if the stamps are off, the result is off "
                           "along the direction of travel",
                           1000.0 * t.time_offset_s);
    out.push_back({hopeless ? Verdict::kCollectMore : Verdict::kUsable, resolves + consequence + what_to_do});
  }
  if (estimated) {
    if (t.halfwidth_ms && *t.halfwidth_ms > c.good_time_offset_ms) {
      out.push_back({*t.halfwidth_ms > c.usable_time_offset_ms ? Verdict::kCollectMore : Verdict::kUsable,
                     format("timing: the time offset %.1f ms is uncertain by +-%.1f ms (good <= %.3g)",
                            1000.0 * t.time_offset_s, *t.halfwidth_ms, c.good_time_offset_ms) +
                         what_to_do});
    }
    return;
  }
  if (!t.probe_offset_s) return;
  const double moved_ms = 1000.0 * std::abs(*t.probe_offset_s - t.time_offset_s);
  const double gain = t.fit_loss > 0.0 ? 1.0 - t.probe_loss / t.fit_loss : 0.0;
  if (moved_ms >= c.timing_probe_ms && gain >= c.timing_min_gain) {
    out.push_back({Verdict::kCollectMore,
                   format("timing: the residuals follow the people's motion: the image and scan stamps "
                          "look %.0f ms apart (the fit's loss falls by %.0f %% there), so the result is "
                          "off along the direction of travel",
                          1000.0 * *t.probe_offset_s, 100.0 * gain) +
                       ": set time_offset_mode estimate, or fix the camera driver's time offset (or "
                       "time_offset_s with time_offset_mode fixed)"});
  }
}

void judgeCoverage(const Coverage& cov, const VerdictConfig& c, std::vector<Finding>& out,
                   std::vector<std::string>& missing) {
  const double pairs = static_cast<double>(cov.pairs);
  if (pairs < c.good_pairs) {
    out.push_back({pairs < c.usable_pairs ? Verdict::kCollectMore : Verdict::kUsable,
                   format("only %.0f pairs used (usable from %.0f, good from %.0f)", pairs,
                          c.usable_pairs, c.good_pairs) +
                       ": keep collecting"});
  }
  for (int third = 0; third < 3; ++third) {
    const double f = cov.thirdFraction(third);
    if (f >= c.good_third_fraction) continue;
    const std::string where = std::string(imageThirdName(third)) + " third of the image";
    if (f < c.usable_third_fraction) missing.push_back(imageThirdName(third));
    out.push_back({f < c.usable_third_fraction ? Verdict::kCollectMore : Verdict::kUsable,
                   (f == 0.0 ? "no people in the " + where
                             : "few people in the " + where +
                                   format(" (%.1f %% of the person pixels)", 100.0 * f)) +
                       ": have people walk there"});
  }
  const auto range_finding = [&](std::size_t count, int minimum, const std::string& what,
                                 const std::string& todo) {
    if (static_cast<int>(count) >= minimum) return;
    out.push_back(
        {count == 0 ? Verdict::kCollectMore : Verdict::kUsable,
         (count == 0   ? "no people "
          : count == 1 ? std::string("only 1 person ")
                       : format("only %.0f people ", count)) +
             what + ": " + todo});
  };
  const std::string split = format("%.3g m", cov.near_far_split_m);
  range_finding(cov.people_near, c.min_people_near, "nearer than " + split,
                "have people walk closer to the vehicle (near people pin the translation)");
  range_finding(cov.people_far, c.min_people_far, "farther than " + split,
                "have people walk farther away (far people pin the rotation)");
  const double places = static_cast<double>(cov.distinct_positions);
  if (places < c.good_distinct_positions) {
    out.push_back({places < c.usable_distinct_positions ? Verdict::kCollectMore : Verdict::kUsable,
                   format("people stood in only %.0f distinct places (good from %.0f)", places,
                          c.good_distinct_positions) +
                       ": have them walk around while the vehicle moves"});
  }
}

}  // namespace

const char* toString(Verdict verdict) {
  switch (verdict) {
    case Verdict::kGood:
      return "good";
    case Verdict::kUsable:
      return "usable";
    default:
      return "collect_more";
  }
}

const ParameterRanges<VerdictConfig>& VerdictConfig::ranges() {
  static const auto ranges = ParameterRanges<VerdictConfig>()
      .add("quality_good_rotation_deg", &VerdictConfig::good_rotation_deg, aboveRange(0, 180))
      .add("quality_usable_rotation_deg", &VerdictConfig::usable_rotation_deg, aboveRange(0, 180))
      .add("quality_good_translation_cm", &VerdictConfig::good_translation_cm, aboveRange(0, 1000))
      .add("quality_usable_translation_cm", &VerdictConfig::usable_translation_cm, aboveRange(0, 1000))
      .add("quality_good_pairs", &VerdictConfig::good_pairs, IntRange{1, 100000})
      .add("quality_usable_pairs", &VerdictConfig::usable_pairs, IntRange{1, 100000})
      .add("quality_good_third_fraction", &VerdictConfig::good_third_fraction, closedRange(0, 1.0 / 3.0))
      .add("quality_usable_third_fraction", &VerdictConfig::usable_third_fraction, closedRange(0, 1.0 / 3.0))
      .add("quality_min_people_near", &VerdictConfig::min_people_near, IntRange{0, 100000})
      .add("quality_min_people_far", &VerdictConfig::min_people_far, IntRange{0, 100000})
      .add("quality_good_distinct_positions", &VerdictConfig::good_distinct_positions, IntRange{0, 100000})
      .add("quality_usable_distinct_positions", &VerdictConfig::usable_distinct_positions, IntRange{0, 100000})
      .add("quality_max_loss_px", &VerdictConfig::max_loss_px, closedRange(0, 1e6))
      .add("quality_good_time_offset_ms", &VerdictConfig::good_time_offset_ms, closedRange(0, 1e4))
      .add("quality_usable_time_offset_ms", &VerdictConfig::usable_time_offset_ms, closedRange(0, 1e4))
      .add("quality_good_time_resolution_ms", &VerdictConfig::good_time_resolution_ms, closedRange(0, 1e4))
      .add("quality_timing_probe_ms", &VerdictConfig::timing_probe_ms, closedRange(0, 1e4))
      .add("quality_timing_min_gain", &VerdictConfig::timing_min_gain, closedRange(0, 1));
  return ranges;
}

void VerdictConfig::validate() const {
  ranges().check(*this);
  requireOrder("quality_good_time_offset_ms", good_time_offset_ms, "quality_usable_time_offset_ms",
               usable_time_offset_ms, true);
  requireOrder("quality_good_rotation_deg", good_rotation_deg, "quality_usable_rotation_deg",
               usable_rotation_deg, true);
  requireOrder("quality_good_translation_cm", good_translation_cm, "quality_usable_translation_cm",
               usable_translation_cm, true);
  requireOrder("quality_good_pairs", good_pairs, "quality_usable_pairs", usable_pairs, false);
  requireOrder("quality_good_third_fraction", good_third_fraction, "quality_usable_third_fraction",
               usable_third_fraction, false);
  requireOrder("quality_good_distinct_positions", good_distinct_positions,
               "quality_usable_distinct_positions", usable_distinct_positions, false);
}

VerdictReport judgeQuality(const Coverage& coverage, const std::optional<Uncertainty>& uncertainty,
                           const VerdictConfig& config, std::optional<double> fit_loss_px,
                           const std::optional<TimingAssessment>& timing) {
  config.validate();
  std::vector<Finding> findings;
  VerdictReport report;
  if (fit_loss_px && !(*fit_loss_px <= config.max_loss_px)) {
    // First: intervals and coverage say nothing useful about a fit that does not fit.
    findings.push_back(
        {Verdict::kCollectMore,
         format("the fit leaves the people's points %.3g px off their masks on average (at most %.3g)",
                *fit_loss_px, config.max_loss_px) +
             ": the pairs disagree (the image and the cloud show different objects) or the search "
             "failed; check the detections and lidar_min/max_azimuth_deg, then collect more"});
  }
  if (timing) judgeTiming(*timing, config, findings);
  judgeCoverage(coverage, config, findings, report.missing_regions);
  if (uncertainty && uncertainty->resamples >= 2) {
    judgeUncertainty(*uncertainty, config, findings);
  } else {
    findings.push_back(
        {Verdict::kUsable, "no uncertainty estimate yet: the verdict rests on coverage alone"});
  }
  std::stable_sort(findings.begin(), findings.end(),
                   [](const Finding& a, const Finding& b) { return a.level > b.level; });
  report.verdict = Verdict::kGood;
  for (const Finding& f : findings) {
    report.verdict = std::max(report.verdict, f.level);
    report.reasons.push_back(f.text);
  }
  if (report.reasons.empty()) {
    report.reasons.push_back(
        format("every axis within +-%.3g deg / +-%.3g cm, people across the whole image, near "
               "and far",
               config.good_rotation_deg, config.good_translation_cm));
  }
  return report;
}

}  // namespace thermal_lidar_calibration
