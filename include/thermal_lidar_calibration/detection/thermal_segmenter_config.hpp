#pragma once
// Settings of the thermal person segmenter. The member initialisers are the defaults; every
// threshold carries its unit and allowed range, and validate() names the key, the value and the
// range of the first bad one (the keys are the flat parameter keys of config/default.yaml).

#include "thermal_lidar_calibration/core/parameter_range.hpp"

#include <string>

namespace thermal_lidar_calibration {
namespace detection {

// How pixel values are read.
enum class ThermalScale {
  kAuto,      // 16-bit with kelvin_per_count > 0: radiometric; otherwise relative
  kRelative,  // always relative to the frame (uncalibrated cores, AGC-mapped 8-bit video)
};

struct ThermalSegmenterConfig {
  // --- Radiometric scale of 16-bit images: kelvin = counts * kelvin_per_count + kelvin_offset.
  double kelvin_per_count = 0.04;  // K per count; 0 = not radiometric; [0, 10]
  double kelvin_offset = 0.0;      // K; [-10000, 10000]
  ThermalScale scale = ThermalScale::kAuto;  // thermal_scale: auto | relative

  // --- Radiometric mode: a person pixel is in the body-surface band AND warmer than the scene.
  double body_min_k = 295.0;      // thermal_body_min_k: coolest apparent body surface (clothed), K; [150, 400]
  double body_max_k = 312.0;      // thermal_body_max_k: warmest (bare skin ~306-309 K), K; (150, 500], above thermal_body_min_k
  double min_contrast_k = 3.0;    // thermal_min_contrast_k: above the frame's background level, K; [0, 100]

  // --- Relative mode (8-bit, or 16-bit not radiometric): threshold between the background
  // level and the frame's warm tail, never closer to the background than a noise margin.
  double relative_threshold = 0.45;        // thermal_relative_threshold: fraction of (warm tail - background); (0, 1]
  double relative_tail_percentile = 99.7;  // thermal_relative_tail_percentile: the warm tail, %; [50, 100]
  double relative_min_contrast_noise = 6.0;  // thermal_relative_min_contrast_noise: floor of the contrast in sigmas of the pixel noise (from neighbouring-pixel differences; at least one grey level); [0, 1000]

  // --- Relative mode: a person is self-heated, and their skin is the warmest thing in a night
  // scene, so the warmest 1 % of a person's pixels reach the frame's warm tail. A region whose
  // warm core stays well below (a reflection of people in a glossy wall, a patch of wall or
  // ground the day warmed) is not a person. The bar is the warm tail, or the core of the warmest
  // region that passed the shape filters if that is lower (a frame where something hotter than
  // people, an engine or a lamp, fills the tail). Radiometric images have the body band instead.
  double relative_min_core = 0.9;  // thermal_relative_min_core: a region's 99th percentile reaches this fraction of the way from the background level to the bar; 0 = off; [0, 1]

  // --- Background level: median of a sub-sampled grid of pixels.
  int background_step_px = 4;  // thermal_background_step_px: sample every n-th pixel in x and y; integer [1, 64]

  // --- Clean-up of the binary mask (square structuring elements of side 2r+1).
  int open_radius_px = 1;   // thermal_open_radius_px: opening removes specks and 1-px bridges; integer [0, 10]
  int close_radius_px = 1;  // thermal_close_radius_px: closing fills small holes and seams; integer [0, 10]
  // The opening also removes the parts of a person narrower than its square (a leg's bottom rows,
  // a far person's 1-2 px legs and arms), where LiDAR points sit: each kept person grows back into
  // the warm pixels connected to it, at most this many 4-neighbour steps (detection/opened_parts.hpp).
  int restore_px = 10;  // thermal_restore_px: 0 = off; integer [0, 50]

  // --- Regions cut by the image border: a region with a pixel in the outermost border_margin_px
  // rows or columns may go on outside the frame, so its shape says nothing, and the LiDAR points
  // of that person would project partly outside the image: useless for calibration. Dropped and
  // counted (ThermalSegmentation::border_cut).
  int border_margin_px = 1;  // thermal_border_margin_px: px; 0 = keep them; integer [0, 1000]

  // --- Size floor from geometry: the smallest a person looks at the farthest range the
  // calibration pairs (the LiDAR detector's lidar_max_range_m) through this camera's lens, with
  // the focal length f = (image width / 2) / tan(hfov / 2): a region at least
  // f * min_person_height_m / max_range_m px tall and f^2 * min_person_area_m2 / max_range_m^2 px
  // large (thermal_min_height_px and thermal_min_area_px stay as floors of their own). A warm spot
  // below it is no person at any range that matters. The smallest silhouette is the head and
  // torso of a small adult (0.8 m tall, 0.15 m^2 side on): the legs of a far person are only 2-4
  // px wide and may go with the opening, or be as cold as the ground. (A standing adult shows
  // ~0.5 m^2 facing the camera, ~0.3 m^2 side on.)
  double camera_hfov_deg = 45.0;      // thermal_camera_hfov_deg: horizontal field of view of the images as given, deg (FLIR A65: 45); (0, 170] (a pinhole view)
  double max_range_m = 30.0;          // thermal_max_range_m: farthest person to find, m (lidar_max_range_m's default); (0, 10000]
  double min_person_height_m = 0.8;   // thermal_min_person_height_m: height of the smallest warm silhouette, m; [0, 3]
  double min_person_area_m2 = 0.15;   // thermal_min_person_area_m2: area of the smallest warm silhouette, m^2; [0, 5]

  // --- Shape filters per connected component (8-connected).
  int min_area_px = 80;             // thermal_min_area_px: pixels (a person ~45 m from a FLIR A65); integer [1, 10000000]
  double max_area_fraction = 0.1;   // thermal_max_area_fraction: of the image area (a person ~4 m from a FLIR A65); (0, 1]
  int min_height_px = 16;           // thermal_min_height_px: bounding-box height, px (a person ~85 m from a FLIR A65); integer [1, 100000]
  double min_aspect = 1.5;          // thermal_min_aspect: bounding-box height / width (animals side on ~1.1-1.3, people >= 1.6); (0, 100]
  double max_aspect = 8.0;          // thermal_max_aspect: height / width (people side on with legs together reach ~7; thinner is a pole); (0, 100], >= thermal_min_aspect
  double min_fill = 0.30;           // thermal_min_fill: area / bounding-box area; [0, 1]
  double max_fill = 0.95;           // thermal_max_fill: area / bounding-box area; [0, 1], >= thermal_min_fill
  // A slender region (height / width at least straight_min_aspect) is a post, not a person, when
  // its legs zone (rows 10-40 % of its height above its bottom) is as wide as its torso zone
  // (50-80 %): median row extents within a ratio r in [straight_ratio, 1 / r], or the region is
  // too narrow to tell (at most 1 / (1 - r) px: 5 px for r = 0.8; a person ~35 m away side on). A person's legs together are ~0.5-0.6 of the torso (side on or facing), striding legs
  // wider than it; a post or pole is as wide at the bottom as at the top, slanted or not. Not
  // applied to the parts of a region split at heads (their cut sides say nothing).
  double straight_min_aspect = 3.5;  // thermal_straight_min_aspect: height / width; (0, 100]
  double straight_ratio = 0.8;       // thermal_straight_ratio: r; (0, 1]
  // A person's vertical profile: a head on a neck narrower than the shoulders. The narrowest row
  // of the neck zone (8-22 % of the height from the top) is at most max_neck_ratio times the
  // torso zone's median row (20-50 %). People measured 0.2-0.6 (LLVIP: facing, walking, on
  // bicycles, seen from above), a warm car bonnet 1.05 and a pair of legs split off at the belt
  // 0.93. Applied below straight_min_aspect only: a slender region has the straight-sides test,
  // and a far person side on is a dozen pixels wide, the neck a pixel or two narrower than the
  // torso (the synthetic drives' people at 20 m measured up to 0.8).
  double max_neck_ratio = 0.75;      // thermal_max_neck_ratio: 0 = off; [0, 10]

  // --- People side by side in one region: a region whose height / width is below
  // split_max_aspect is cut where its top profile dips head_dip_fraction of its height between
  // two heads; each part then passes the shape filters on its own. A region that is no person as
  // a whole is also cut at half that dip (heads touching), kept cut only when every part of a
  // person's size is a person.
  double split_max_aspect = 3.0;     // thermal_split_max_aspect: one person standing is ~3-4, two side by side ~2; (0, 100]
  double head_dip_fraction = 0.08;   // thermal_head_dip_fraction: of the region's height; (0, 1]

  // --- Ground-plane size check (detection/person_size_model.hpp): a candidate much shorter
  // than the people recent frames showed with their feet at the same image row is not a person
  // (an animal end on). Needs a stream of frames; a single image is never judged.
  int size_history = 300;      // thermal_size_history: candidates remembered; 0 = off; integer [0, 100000]
  int size_min_samples = 60;   // thermal_size_min_samples: candidates before it judges; integer [10, 100000]
  double size_min_ratio = 0.7; // thermal_size_min_ratio: of a person's height at that foot row; [0, 1]

  static const ParameterRanges<ThermalSegmenterConfig>& ranges();  // checked by validate()

  void validate() const;  // throws std::invalid_argument naming key, value and range
};

// "auto" / "relative" <-> ThermalScale; parse throws std::invalid_argument naming the key.
ThermalScale parseThermalScale(const std::string& text);
const char* toString(ThermalScale scale);

}  // namespace detection
}  // namespace thermal_lidar_calibration
