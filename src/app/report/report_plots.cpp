// The report's pictures: convergence, per-pair loss, uncertainty, coverage, pair overlays.

#include "thermal_lidar_calibration/app/report/report_plots.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>

namespace thermal_lidar_calibration {
namespace {

const cv::Scalar kBlack(0, 0, 0), kGrey(170, 170, 170), kBlue(200, 90, 20), kRed(40, 40, 220);
const cv::Scalar kGreen(60, 170, 60), kYellow(0, 200, 230), kWhite(255, 255, 255);

std::string format(const char* spec, double v) {
  char text[64];
  std::snprintf(text, sizeof(text), spec, v);
  return text;
}

void text(cv::Mat& img, const std::string& s, cv::Point at, double scale = 0.5,
          const cv::Scalar& colour = kBlack) {
  cv::putText(img, s, at, cv::FONT_HERSHEY_SIMPLEX, scale, colour, 1, cv::LINE_AA);
}

// A plot area with a title, and the mapping from values to pixels.
struct PlotFrame {
  cv::Mat img;
  cv::Rect area;
  PlotFrame(int width, int height, const std::string& title, int left = 70) {
    img = cv::Mat(height, width, CV_8UC3, kWhite);
    area = cv::Rect(left, 35, width - left - 20, height - 35 - 45);
    cv::rectangle(img, area, kGrey, 1);
    text(img, title, {left, 22}, 0.55);
  }
  int x(double fraction) const { return area.x + static_cast<int>(std::lround(fraction * area.width)); }
  int y(double fraction) const {  // 0 = bottom, 1 = top
    return area.y + area.height - static_cast<int>(std::lround(fraction * area.height));
  }
};

}  // namespace

cv::Mat drawConvergence(const std::vector<ConvergenceStep>& history, int width, int height) {
  PlotFrame f(width, height, "convergence: best loss per generation (each stage), then the refinement");
  if (history.empty()) {
    text(f.img, "no history (the run recorded none)", {f.area.x + 20, f.area.y + 40});
    return f.img;
  }
  double lo = 1e300, hi = 0.0;
  for (const auto& s : history) {
    if (s.best_loss > 0) lo = std::min(lo, s.best_loss), hi = std::max(hi, s.best_loss);
  }
  if (!(hi > 0)) lo = 1e-3, hi = 1.0;
  if (hi <= lo * 1.0001) hi = lo * 10.0;
  const double llo = std::log10(lo), lhi = std::log10(hi);
  const auto yOf = [&](double v) { return f.y((std::log10(std::max(v, lo)) - llo) / (lhi - llo)); };
  for (int d = static_cast<int>(std::floor(llo)); d <= static_cast<int>(std::ceil(lhi)); ++d) {
    const double v = std::pow(10.0, d);
    if (v < lo * 0.999 || v > hi * 1.001) continue;
    cv::line(f.img, {f.area.x, yOf(v)}, {f.area.x + f.area.width, yOf(v)}, {230, 230, 230});
    text(f.img, format("%g px", v), {4, yOf(v) + 4}, 0.4);
  }
  text(f.img, format("%.3g px", hi), {4, f.area.y + 12}, 0.4);
  text(f.img, format("%.3g px", lo), {4, f.area.y + f.area.height}, 0.4);
  const cv::Scalar palette[] = {kBlue, {40, 150, 40}, {160, 60, 160}, kRed, {0, 140, 220}, {90, 90, 90}};
  std::map<std::string, int> colour_of;
  const double n = static_cast<double>(std::max<std::size_t>(history.size() - 1, 1));
  cv::Point previous;
  std::string previous_stage;
  int legend_x = f.area.x;
  for (std::size_t i = 0; i < history.size(); ++i) {
    const auto& s = history[i];
    const std::string stage = s.stage.rfind("refine", 0) == 0 ? "refine" : s.stage;
    if (!colour_of.count(stage)) {
      const int c = static_cast<int>(colour_of.size()) % 6;
      colour_of[stage] = c;
      text(f.img, stage, {legend_x, height - 12}, 0.45, palette[c]);
      legend_x += 20 + 9 * static_cast<int>(stage.size());
    }
    const cv::Point p(f.x(static_cast<double>(i) / n), yOf(s.best_loss));
    if (stage == previous_stage) {
      cv::line(f.img, previous, p, palette[colour_of[stage]], 2, cv::LINE_AA);
    } else {
      cv::line(f.img, {p.x, f.area.y}, {p.x, f.area.y + f.area.height}, {220, 220, 220});
    }
    previous = p;
    previous_stage = stage;
  }
  return f.img;
}

cv::Mat drawPairLosses(const std::vector<double>& pair_losses, const std::vector<bool>& inliers,
                       double threshold_px, int width, int height) {
  PlotFrame f(width, height, "loss per pair at the result (Eq. 1, px): used (blue), outliers (red)");
  if (pair_losses.empty()) return f.img;
  double hi = threshold_px * 1.5;
  for (double v : pair_losses) hi = std::max(hi, std::isfinite(v) ? v : 0.0);
  hi = std::min(hi, threshold_px * 20.0);  // a far outlier must not flatten the rest
  const double n = static_cast<double>(pair_losses.size());
  const int bar = std::max(1, static_cast<int>(f.area.width / n) - 1);
  for (std::size_t i = 0; i < pair_losses.size(); ++i) {
    const double v = std::isfinite(pair_losses[i]) ? std::min(pair_losses[i], hi) : hi;
    const bool used = i < inliers.size() && inliers[i];
    const int x0 = f.x(static_cast<double>(i) / n);
    cv::rectangle(f.img, cv::Point(x0, f.y(v / hi)), cv::Point(x0 + bar - 1, f.y(0)),
                  used ? kBlue : kRed, cv::FILLED);
  }
  const int ty = f.y(threshold_px / hi);
  for (int x = f.area.x; x < f.area.x + f.area.width; x += 12) {
    cv::line(f.img, {x, ty}, {std::min(x + 6, f.area.x + f.area.width), ty}, kBlack, 1);
  }
  text(f.img, format("threshold %.2f px", threshold_px), {f.area.x + f.area.width - 150, ty - 5}, 0.45);
  text(f.img, format("%.3g", hi), {8, f.area.y + 12}, 0.45);
  text(f.img, "0", {40, f.y(0)}, 0.45);
  text(f.img, "pairs in time order", {f.area.x, height - 15}, 0.45);
  return f.img;
}

cv::Mat drawTimeOffsetProfile(const std::vector<double>& offsets_s, const std::vector<double>& losses_px,
                              double result_s, double halfwidth_ms, int width, int height) {
  PlotFrame f(width, height, "loss along the camera's time offset (px; the pose refined at each offset)");
  std::vector<std::pair<double, double>> points;  // (ms, px), finite only
  for (std::size_t i = 0; i < std::min(offsets_s.size(), losses_px.size()); ++i) {
    if (std::isfinite(losses_px[i])) points.emplace_back(1000.0 * offsets_s[i], losses_px[i]);
  }
  if (points.size() < 2) {
    text(f.img, "no profile (the offset was not searched)", {f.area.x + 20, f.area.y + 40});
    return f.img;
  }
  double lo = points.front().first, hi = points.front().first, top = 0.0;
  for (const auto& p : points) lo = std::min(lo, p.first), hi = std::max(hi, p.first), top = std::max(top, p.second);
  if (!(hi > lo)) hi = lo + 1.0;
  if (!(top > 0)) top = 1.0;
  const auto px = [&](double ms) { return f.x((ms - lo) / (hi - lo)); };
  const double result_ms = 1000.0 * result_s;
  if (halfwidth_ms > 0) {
    cv::rectangle(f.img, cv::Point(px(std::max(lo, result_ms - halfwidth_ms)), f.y(1)),
                  cv::Point(px(std::min(hi, result_ms + halfwidth_ms)), f.y(0)), cv::Scalar(235, 225, 210), cv::FILLED);
  }
  for (std::size_t i = 1; i < points.size(); ++i) {
    cv::line(f.img, {px(points[i - 1].first), f.y(points[i - 1].second / top)},
             {px(points[i].first), f.y(points[i].second / top)}, kBlue, 2, cv::LINE_AA);
  }
  for (const auto& p : points) cv::circle(f.img, {px(p.first), f.y(p.second / top)}, 3, kBlue, cv::FILLED);
  if (result_ms >= lo && result_ms <= hi) {
    cv::line(f.img, {px(result_ms), f.y(0)}, {px(result_ms), f.y(1)}, kRed, 1);
    text(f.img, format("result %+.1f ms", result_ms), {px(result_ms) + 5, f.area.y + 15}, 0.45, kRed);
  }
  text(f.img, format("%.3g", top), {8, f.area.y + 12}, 0.45);
  text(f.img, "0", {40, f.y(0)}, 0.45);
  text(f.img, format("%+.0f ms", lo), {f.area.x, height - 25}, 0.45);
  text(f.img, format("%+.0f ms", hi), {f.area.x + f.area.width - 60, height - 25}, 0.45);
  text(f.img, "time offset (the image stamped t shows the world at t + offset)", {f.area.x + 120, height - 10}, 0.45);
  return f.img;
}

cv::Mat drawUncertainty(const Uncertainty& u, int width, int height) {
  PlotFrame f(width, height, "95 % interval half-width per camera axis (bootstrap over pairs)", 20);
  const char* names[6] = {"rot x", "rot y", "rot z", "t x", "t y", "t z"};
  const int half = f.area.width / 2;
  for (int group = 0; group < 2; ++group) {
    double hi = 1e-9;
    for (int k = 3 * group; k < 3 * group + 3; ++k) hi = std::max(hi, u.halfWidth(k));
    hi *= 1.25;
    text(f.img, group == 0 ? "rotation, deg" : "translation, cm", {f.area.x + group * half + 10, f.area.y + 18});
    for (int j = 0; j < 3; ++j) {
      const int k = 3 * group + j;
      const int x0 = f.area.x + group * half + 30 + j * (half - 40) / 3;
      const int w = (half - 40) / 3 - 30;
      const int top = f.y(0.85 * u.halfWidth(k) / hi);
      cv::rectangle(f.img, {x0, top}, {x0 + w, f.y(0)}, group == 0 ? kBlue : cv::Scalar(40, 150, 40), cv::FILLED);
      text(f.img, format(group == 0 ? "+-%.3f" : "+-%.2f", u.halfWidth(k)), {x0, top - 6}, 0.45);
      text(f.img, names[k], {x0, f.y(0) + 18}, 0.45);
    }
  }
  text(f.img, u.method() + ", " + std::to_string(u.pairs) + " pairs", {f.area.x, height - 10}, 0.45);
  return f.img;
}

cv::Mat drawCoverage(const Coverage& c, int width, int height) {
  cv::Mat img(height, width, CV_8UC3, kWhite);
  if (c.grid_columns <= 0 || c.grid_rows <= 0) return img;
  double most = 0.0;
  for (int r = 0; r < c.grid_rows; ++r) {
    for (int col = 0; col < c.grid_columns; ++col) most = std::max(most, c.gridFraction(r, col));
  }
  const double cw = static_cast<double>(width) / c.grid_columns;
  const double ch = static_cast<double>(height - 30) / c.grid_rows;
  for (int r = 0; r < c.grid_rows; ++r) {
    for (int col = 0; col < c.grid_columns; ++col) {
      const double share = c.gridFraction(r, col);
      const cv::Rect cell(static_cast<int>(col * cw), 30 + static_cast<int>(r * ch),
                          static_cast<int>(cw) - 1, static_cast<int>(ch) - 1);
      const int level = most > 0 ? static_cast<int>(255 * share / most) : 0;
      cv::Mat swatch(1, 1, CV_8UC1, cv::Scalar(level)), colour;
      cv::applyColorMap(swatch, colour, cv::COLORMAP_INFERNO);
      const cv::Vec3b v = colour.at<cv::Vec3b>(0, 0);
      cv::rectangle(img, cell, cv::Scalar(v[0], v[1], v[2]), cv::FILLED);
      const std::string label = share > 0 ? format("%.1f %%", 100 * share) : "empty";
      text(img, label, {cell.x + 8, cell.y + cell.height / 2}, 0.5, level > 140 ? kBlack : kWhite);
    }
  }
  text(img, "where the people were: share of person pixels per image cell, " +
                std::to_string(c.pairs) + " pairs", {8, 20}, 0.45);
  return img;
}

cv::Mat drawPairOverlay(const CameraModel& camera, const CalibrationPair& pair,
                        const Extrinsic& estimate, const std::string& caption) {
  cv::Mat gray8;
  const cv::Mat& source = pair.image.empty() ? pair.mask : pair.image;
  if (source.depth() == CV_8U && !pair.image.empty()) {
    gray8 = source;
  } else {
    double lo = 0.0, hi = 0.0;
    cv::minMaxLoc(source, &lo, &hi);
    const double scale = hi > lo ? (pair.image.empty() ? 90.0 : 255.0) / (hi - lo) : 1.0;
    source.convertTo(gray8, CV_8U, scale, -lo * scale);
  }
  cv::Mat out;
  cv::cvtColor(gray8, out, cv::COLOR_GRAY2BGR);
  const cv::Mat binary = pair.mask != 0;
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(binary, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE);
  cv::drawContours(out, contours, -1, kWhite, 1);
  cv::Mat distance;  // px to the nearest person pixel (0 on the mask)
  cv::distanceTransform(binary == 0, distance, cv::DIST_L2, 3);
  const Eigen::Matrix3d R = estimate.rotationMatrix();
  for (const Eigen::Vector3f& p : pair.points) {
    const Eigen::Vector3d pc = R * p.cast<double>() + estimate.translation;
    if (pc.z() <= 0.05) continue;
    const Eigen::Vector2d uv = camera.project(pc);
    const int u = static_cast<int>(std::lround(uv.x())), v = static_cast<int>(std::lround(uv.y()));
    if (u < 0 || v < 0 || u >= out.cols || v >= out.rows) continue;
    const float d = distance.at<float>(v, u);
    cv::circle(out, {u, v}, 2, d < 0.5f ? kGreen : d <= 3.0f ? kYellow : kRed, cv::FILLED);
  }
  cv::rectangle(out, {0, 0}, {out.cols, 24}, kBlack, cv::FILLED);
  text(out, caption, {6, 17}, 0.5, kWhite);
  return out;
}

}  // namespace thermal_lidar_calibration
