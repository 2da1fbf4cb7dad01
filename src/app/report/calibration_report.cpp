// The visual report: the pictures (report_plots) written as PNG files and an index.html.

#include "thermal_lidar_calibration/app/report/calibration_report.hpp"

#include "thermal_lidar_calibration/app/report/report_plots.hpp"
#include "thermal_lidar_calibration/app/report/timing_text.hpp"
#include "thermal_lidar_calibration/core/person_timing.hpp"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace thermal_lidar_calibration {
namespace {

std::string format(const char* spec, double a, double b = 0, double c = 0) {
  char text[256];
  std::snprintf(text, sizeof(text), spec, a, b, c);
  return text;
}

std::string escape(const std::string& s) {
  std::string out;
  for (char ch : s) {
    if (ch == '<') out += "&lt;";
    else if (ch == '>') out += "&gt;";
    else if (ch == '&') out += "&amp;";
    else out += ch;
  }
  return out;
}

// The 3 best and 3 worst pairs by their loss at the result, half size, in a 3 x 2 mosaic: of those
// with a thermal image when any has one (frames the skip rule passed over hold none).
cv::Mat overlayMosaic(const ReportInput& in) {
  const auto& pairs = *in.pairs;
  const auto& losses = in.result->pair_losses;
  const bool images =
      std::any_of(pairs.begin(), pairs.end(), [](const CalibrationPair& p) { return !p.image.empty(); });
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    if (!images || !pairs[i].image.empty()) order.push_back(i);
  }
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return losses.at(a) < losses.at(b);
  });
  std::vector<std::pair<std::size_t, std::string>> chosen;
  for (std::size_t i = 0; i < std::min<std::size_t>(3, order.size()); ++i) chosen.emplace_back(order[i], "best");
  for (std::size_t i = order.size() > 3 ? std::max<std::size_t>(3, order.size() - 3) : order.size();
       i < order.size(); ++i) {
    chosen.emplace_back(order[i], "worst");
  }
  const int tile_w = in.camera->width / 2, tile_h = in.camera->height / 2;
  cv::Mat mosaic(2 * tile_h, 3 * tile_w, CV_8UC3, cv::Scalar(255, 255, 255));
  for (std::size_t k = 0; k < chosen.size(); ++k) {
    const std::size_t i = chosen[k].first;
    const bool used = i < in.result->inliers.size() && in.result->inliers[i];
    // Drawn as the fit saw the pair: its people where they were at the image's instant.
    CalibrationPair at_image = pairs[i];
    if (in.result->time_offset_mode != TimeOffsetMode::kNone) {
      at_image.points = pointsAtImageTime(pairs[i], in.result->time_offset_s);
    }
    const cv::Mat full = drawPairOverlay(
        *in.camera, at_image, in.result->extrinsic,
        chosen[k].second + ": pair " + std::to_string(i) + format(", %.2f px", losses[i]) +
            (used ? ", used" : ", outlier"));
    cv::Mat tile;
    cv::resize(full, tile, cv::Size(tile_w, tile_h), 0, 0, cv::INTER_AREA);
    const int slot = static_cast<int>(k);  // best in the top row, worst below
    tile.copyTo(mosaic(cv::Rect((slot % 3) * tile_w, (slot / 3) * tile_h, tile_w, tile_h)));
  }
  return mosaic;
}

void writePng(const std::string& path, const cv::Mat& image, std::vector<std::string>& written) {
  if (!cv::imwrite(path, image)) throw std::runtime_error("cannot write the report picture " + path);
  written.push_back(path);
}

std::string resultTable(const ReportInput& in) {
  const CalibrationResult& r = *in.result;
  std::string html = "<table>\n";
  const auto row = [&](const std::string& k, const std::string& v) {
    html += "<tr><th>" + escape(k) + "</th><td>" + escape(v) + "</td></tr>\n";
  };
  row("frames", in.lidar_frame + " -> " + in.camera_frame + " (p_C = R p_L + t)");
  row("rotation vector (rad)", format("[%.6f, %.6f, %.6f]", r.extrinsic.rotation_vector.x(),
                                      r.extrinsic.rotation_vector.y(), r.extrinsic.rotation_vector.z()));
  row("translation (m)", format("[%.4f, %.4f, %.4f]", r.extrinsic.translation.x(),
                                r.extrinsic.translation.y(), r.extrinsic.translation.z()));
  row("loss (Eq. 3, nearest pixel)", format("%.4f px (sub-pixel %.4f px)", r.loss, r.loss_bilinear));
  row("pairs", std::to_string(r.pairs_used) + " used of " + std::to_string(r.pairs_collected) + " kept");
  row("run time", format("%.1f s, %.0f loss evaluations", r.seconds, static_cast<double>(r.evaluations)));
  row("camera time offset", timeOffsetText(r, in.quality ? in.quality->uncertainty : std::nullopt));
  if (in.quality) {
    const QualityAssessment& q = *in.quality;
    row("verdict", toString(q.verdict.verdict));
    for (const auto& reason : q.verdict.reasons) row("", reason);
    if (q.uncertainty) {
      const auto& u = *q.uncertainty;
      row("rotation 95 % +- (deg, camera x y z)",
          format("%.3f, %.3f, %.3f", u.rotation_deg.x(), u.rotation_deg.y(), u.rotation_deg.z()));
      row("translation 95 % +- (cm, camera x y z)",
          format("%.2f, %.2f, %.2f", u.translation_cm.x(), u.translation_cm.y(), u.translation_cm.z()));
    }
    if (q.reference) {
      const auto& c = *q.reference;
      row("calibration in use", c.origin);
      row("difference: rotation (deg, x y z)",
          format("%.3f, %.3f, %.3f", c.difference.rotation_deg.x(), c.difference.rotation_deg.y(),
                 c.difference.rotation_deg.z()));
      row("difference: translation (cm, x y z)",
          format("%.2f, %.2f, %.2f", c.difference.translation_cm.x(), c.difference.translation_cm.y(),
                 c.difference.translation_cm.z()));
      row("loss on the same pairs", format("in use %.4f px, ours %.4f px (%.0f pairs)", c.reference_loss,
                                           c.our_loss, static_cast<double>(c.pairs)));
    }
  }
  return html + "</table>\n";
}

}  // namespace

std::vector<std::string> writeCalibrationReport(const std::string& dir, const ReportInput& in) {
  if (!in.camera || !in.pairs || !in.result) throw std::invalid_argument("report: no result");
  if (in.result->pair_losses.size() != in.pairs->size()) {
    throw std::invalid_argument("report: the result does not belong to the pairs");
  }
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (error) throw std::runtime_error("cannot make the report directory " + dir + ": " + error.message());
  std::vector<std::string> written;
  const std::string d = dir + "/";
  writePng(d + "overlays.png", overlayMosaic(in), written);
  if (in.quality) writePng(d + "coverage.png", drawCoverage(in.quality->coverage), written);
  writePng(d + "convergence.png", drawConvergence(in.result->history), written);
  writePng(d + "pair_losses.png",
           drawPairLosses(in.result->pair_losses, in.result->inliers, in.threshold_px), written);
  const bool uncertainty = in.quality && in.quality->uncertainty;
  if (uncertainty) writePng(d + "uncertainty.png", drawUncertainty(*in.quality->uncertainty), written);
  const bool profile = !in.result->time_offset_profile_s.empty();
  if (profile) {
    const double halfwidth = uncertainty && in.quality->uncertainty->timed ? in.quality->uncertainty->time_offset_ms : 0.0;
    writePng(d + "time_offset.png",
             drawTimeOffsetProfile(in.result->time_offset_profile_s, in.result->time_offset_profile_loss,
                                   in.result->time_offset_s, halfwidth),
             written);
  }

  std::string html =
      "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>thermal_lidar_calibration "
      "report</title>\n<style>body{font-family:sans-serif;max-width:1000px;margin:auto}"
      "th{text-align:left;padding-right:1em;vertical-align:top}img{max-width:100%;"
      "border:1px solid #ccc}</style></head><body>\n<h1>Thermal camera - LiDAR calibration</h1>\n<p>" +
      escape(in.source) + "</p>\n" + resultTable(in) +
      "<h2>Overlays: the 3 best and the 3 worst pairs</h2>\n<p>LiDAR person points projected with "
      "the result: green on the person mask, yellow within 3 px of it, red beyond. The mask is "
      "outlined in white.</p>\n<img src=\"overlays.png\">\n";
  if (in.quality) html += "<h2>Coverage</h2>\n<img src=\"coverage.png\">\n";
  // The stages read different losses (INTERFACE.md, the rings' ends): say so where the curve jumps.
  html += "<h2>Convergence</h2>\n<p>The evolution's generations read Eq. 3 (nearest pixel). The "
          "refinement's stages read the sub-pixel loss from the person pixels' outline and, in the "
          "default run, each LiDAR ring end's distance from its own person's outline "
          "(<code>refine_ring_end_weight</code>): compare values within a stage, not across.</p>\n"
          "<img src=\"convergence.png\">\n<h2>Loss per pair</h2>\n<img src=\"pair_losses.png\">\n";
  if (uncertainty) html += "<h2>Uncertainty per axis</h2>\n<img src=\"uncertainty.png\">\n";
  if (profile) {
    html += "<h2>Camera time offset</h2>\n<p>The loss with the pose refined at each offset of the coarse "
            "search over the whole range, on the " + std::to_string(in.result->time_offset_profile_pairs) +
            " pairs of the fit that ran it (with association, the first fit: the later rounds search near "
            "its estimate); a clear dip is a drive that tells the offset, a flat floor one that does not. The "
            "overlays above show the people where they were at each image's instant.</p>\n"
            "<img src=\"time_offset.png\">\n";
  }
  html += "</body></html>\n";
  const std::string index = d + "index.html";
  std::ofstream out(index);
  out << html;
  out.close();
  if (!out) throw std::runtime_error("cannot write the report page " + index);
  written.push_back(index);
  return written;
}

}  // namespace thermal_lidar_calibration
