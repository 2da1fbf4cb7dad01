#include "thermal_lidar_calibration/synthetic/noise_model.hpp"

#include <opencv2/imgproc.hpp>

#include <set>
#include <stdexcept>

namespace thermal_lidar_calibration {
namespace synthetic {
namespace {

void requireRate(double value, const char* name) {
  if (!(value >= 0.0 && value <= 1.0)) {
    throw std::invalid_argument(std::string("noise: ") + name + " must be in [0, 1], got " + std::to_string(value));
  }
}

}  // namespace

void NoiseConfig::validate() const {
  if (!(range_sigma_m >= 0.0 && range_sigma_m <= 1.0)) {
    throw std::invalid_argument("noise: range_sigma_m must be in [0, 1] m, got " + std::to_string(range_sigma_m));
  }
  if (mask_edge_px < 0 || mask_edge_px > 20) {
    throw std::invalid_argument("noise: mask_edge_px must be in [0, 20], got " + std::to_string(mask_edge_px));
  }
  requireRate(miss_rate, "miss_rate");
  requireRate(false_cluster_rate, "false_cluster_rate");
  requireRate(false_mask_rate, "false_mask_rate");
  if (!(image_noise >= 0.0 && image_noise <= 50.0)) {
    throw std::invalid_argument("noise: image_noise must be in [0, 50]");
  }
}

NoiseConfig NoiseConfig::clean() { return NoiseConfig{}; }

NoiseConfig NoiseConfig::realistic() {
  NoiseConfig n;
  n.range_sigma_m = 0.02;
  n.mask_edge_px = 2;
  n.miss_rate = 0.03;
  n.false_cluster_rate = 0.03;
  n.false_mask_rate = 0.02;
  return n;
}

NoiseConfig NoiseConfig::preset(const std::string& name) {
  if (name == "clean") return clean();
  if (name == "realistic") return realistic();
  throw std::invalid_argument("unknown noise preset '" + name + "' (use clean or realistic)");
}

MaskEdgeSign maskEdgeSignByName(const std::string& name) {
  if (name == "both") return MaskEdgeSign::kBoth;
  if (name == "grow") return MaskEdgeSign::kGrow;
  if (name == "shrink") return MaskEdgeSign::kShrink;
  throw std::invalid_argument("unknown mask edge sign '" + name + "' (use both, grow or shrink)");
}

const char* toString(MaskEdgeSign sign) {
  switch (sign) {
    case MaskEdgeSign::kGrow: return "grow";
    case MaskEdgeSign::kShrink: return "shrink";
    case MaskEdgeSign::kBoth: break;
  }
  return "both";
}

MaskErosionPart maskErosionPartByName(const std::string& name) {
  if (name == "all") return MaskErosionPart::kAll;
  if (name == "thin") return MaskErosionPart::kThin;
  if (name == "outline") return MaskErosionPart::kOutline;
  throw std::invalid_argument("unknown mask erosion part '" + name + "' (use all, thin or outline)");
}

const char* toString(MaskErosionPart part) {
  switch (part) {
    case MaskErosionPart::kThin: return "thin";
    case MaskErosionPart::kOutline: return "outline";
    case MaskErosionPart::kAll: break;
  }
  return "all";
}

void perturbMaskEdges(cv::Mat& id_mask, int max_px, std::mt19937_64& rng, MaskEdgeSign sign, MaskErosionPart part) {
  if (max_px <= 0 || id_mask.empty()) return;
  cv::Mat ids32;
  id_mask.convertTo(ids32, CV_32S);
  std::set<int> ids;
  for (int r = 0; r < ids32.rows; ++r) {
    const int* row = ids32.ptr<int>(r);
    for (int c = 0; c < ids32.cols; ++c) {
      if (row[c] != 0) ids.insert(row[c]);
    }
  }
  std::uniform_int_distribution<int> amount(sign == MaskEdgeSign::kGrow ? 0 : -max_px,
                                            sign == MaskEdgeSign::kShrink ? 0 : max_px);
  cv::Mat out = ids32.clone();
  for (const int id : ids) {
    const int k = amount(rng);
    if (k == 0) continue;
    const cv::Mat region = ids32 == id;
    const cv::Mat kernel = cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * std::abs(k) + 1, 2 * std::abs(k) + 1));
    if (k > 0) {
      cv::Mat grown;
      cv::dilate(region, grown, kernel);
      out.setTo(id, grown & (ids32 == 0) & (out == 0));
    } else {
      cv::Mat shrunk;
      cv::erode(region, shrunk, kernel);
      if (part != MaskErosionPart::kAll) {
        // The opening (the erosion dilated back within the person) is what keeps no thin part.
        cv::Mat opened;
        cv::dilate(shrunk, opened, kernel);
        opened &= region;
        shrunk = part == MaskErosionPart::kThin ? opened : (shrunk | (region & ~opened));
      }
      out.setTo(0, region & ~shrunk);
    }
  }
  out.convertTo(id_mask, id_mask.type());
}

void addFalseMaskBlob(cv::Mat& id_mask, int id, std::mt19937_64& rng) {
  if (id_mask.empty()) return;
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const int w = 4 + static_cast<int>(unit(rng) * 14.0);
  const int h = static_cast<int>(w * (1.2 + unit(rng) * 1.8));
  const cv::Point centre(static_cast<int>(unit(rng) * id_mask.cols),
                         static_cast<int>(id_mask.rows * (0.25 + 0.6 * unit(rng))));
  cv::ellipse(id_mask, centre, cv::Size(w, h), 0.0, 0.0, 360.0, cv::Scalar(id), cv::FILLED);
}

}  // namespace synthetic
}  // namespace thermal_lidar_calibration
