#pragma once
// Sensor and detector imperfections: LiDAR range noise, mask edge errors, missed people and
// false detections in either modality.

#include <opencv2/core.hpp>

#include <random>
#include <string>

namespace thermal_lidar_calibration {
namespace synthetic {

// Which way a person's mask edge may move: both (a segmentation that is sometimes too large,
// sometimes too small), or only one way (to see what each does to a calibration).
enum class MaskEdgeSign { kBoth, kGrow, kShrink };

// What an erosion takes (issue 24: the two parts lean a calibration opposite ways). kAll: the
// erosion itself. kThin: only the parts narrower than its kernel (far people's legs, arms, heads):
// the person opened with the same kernel, the rest of the outline where it was. kOutline: the
// outline eroded, those thin parts kept whole. Growing is the same for all three.
enum class MaskErosionPart { kAll, kThin, kOutline };

struct NoiseConfig {
  double range_sigma_m = 0.0;       // Gaussian noise along each LiDAR ray, m
  int mask_edge_px = 0;             // each person's mask dilated/eroded by a random 0..N px
  MaskEdgeSign mask_edge_sign = MaskEdgeSign::kBoth;  // kGrow: dilated only; kShrink: eroded only
  MaskErosionPart mask_erosion_part = MaskErosionPart::kAll;  // what an erosion takes
  double miss_rate = 0.0;           // per person, per frame, per modality: detector misses it
  double false_cluster_rate = 0.0;  // per clutter object in range, per frame: reported as a person
  double false_mask_rate = 0.0;     // per frame: one false person blob in the mask
  double image_noise = 1.0;         // thermal image noise, grey levels (mono8 scale)
  void validate() const;            // throws std::invalid_argument

  static NoiseConfig clean();
  // Mask edges +-2 px, 2 cm range noise, 3 % missed people, 3 % false clusters, 2 % false
  // mask blobs.
  static NoiseConfig realistic();
  // "clean" or "realistic"; anything else throws std::invalid_argument.
  static NoiseConfig preset(const std::string& name);
};

// Grows (k > 0) or shrinks (k < 0) each id's region of `id_mask` (CV_8UC1 or CV_16UC1) by an
// independent random k in [-max_px, max_px] (kGrow: [0, max_px]; kShrink: [-max_px, 0]). Growing
// only claims background pixels; shrinking takes what `part` says (the same draws whatever it is).
void perturbMaskEdges(cv::Mat& id_mask, int max_px, std::mt19937_64& rng,
                      MaskEdgeSign sign = MaskEdgeSign::kBoth, MaskErosionPart part = MaskErosionPart::kAll);
// "both", "grow" or "shrink" (and back, as toString(ImageRegion) and toString(LidarStamp)); anything
// else throws std::invalid_argument.
MaskEdgeSign maskEdgeSignByName(const std::string& name);
const char* toString(MaskEdgeSign sign);
// "all", "thin" or "outline", and back; anything else throws std::invalid_argument.
MaskErosionPart maskErosionPartByName(const std::string& name);
const char* toString(MaskErosionPart part);
// Draws a filled ellipse with value `id` somewhere in the mask (a false person blob).
void addFalseMaskBlob(cv::Mat& id_mask, int id, std::mt19937_64& rng);

}  // namespace synthetic
}  // namespace thermal_lidar_calibration
