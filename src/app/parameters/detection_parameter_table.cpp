// The person detectors' parameter table (same machinery and row forms as
// src/app/parameters/core_parameter_table.cpp). Adding a key: a field with its default in the detector's
// Config struct (detection/thermal_segmenter_config.hpp, detection/lidar_detector_config.hpp),
// its range in that struct's ranges(), one row below (kConfigRange); then
// scripts/update_parameter_docs.sh.

#include "thermal_lidar_calibration/app/parameters/detection_parameters.hpp"

#include <cmath>
#include <cstdio>

namespace thermal_lidar_calibration {
namespace {

using detection::LidarGroundConfig;
using detection::LidarPersonConfig;
using detection::ThermalScale;
using detection::ThermalSegmenterConfig;

void addThermalRows(ParameterTable<DetectionParameters>& t) {
  auto th = t.group<ThermalSegmenterConfig>([](DetectionParameters& p) -> ThermalSegmenterConfig& { return p.thermal; });
  t.section("Thermal person segmentation (detectors; issue #7)");
  th.real("kelvin_per_count", &ThermalSegmenterConfig::kelvin_per_count, kConfigRange, "K/count",
          "radiometric scale of 16-bit images: kelvin = counts * kelvin_per_count + kelvin_offset",
          "0 = not radiometric; FLIR Ax5 high-resolution linear 0.04, TLinear cores often 0.01");
  th.real("kelvin_offset", &ThermalSegmenterConfig::kelvin_offset, kConfigRange, "K",
          "radiometric offset (see kelvin_per_count)");
  th.choice("thermal_scale", &ThermalSegmenterConfig::scale,
            {{"auto", ThermalScale::kAuto}, {"relative", ThermalScale::kRelative}}, "must be 'auto' or 'relative'",
            "auto = radiometric for 16-bit images when kelvin_per_count > 0, else relative to the frame");
  th.real("thermal_body_min_k", &ThermalSegmenterConfig::body_min_k, kConfigRange, "K",
          "radiometric: coolest apparent body surface (clothed) counted as a person", "below thermal_body_max_k");
  th.real("thermal_body_max_k", &ThermalSegmenterConfig::body_max_k, kConfigRange, "K",
          "radiometric: warmest apparent body surface (bare skin ~306-309 K); hotter is machinery");
  th.real("thermal_min_contrast_k", &ThermalSegmenterConfig::min_contrast_k, kConfigRange, "K",
          "radiometric: a person pixel is at least this much warmer than the frame's background level");
  th.real("thermal_relative_threshold", &ThermalSegmenterConfig::relative_threshold, kConfigRange, "",
          "relative mode: threshold at this fraction of the way from the background level to the warm tail");
  th.real("thermal_relative_tail_percentile", &ThermalSegmenterConfig::relative_tail_percentile,
          kConfigRange, "%", "relative mode: the warm tail's percentile of the frame");
  th.real("thermal_relative_min_contrast_noise", &ThermalSegmenterConfig::relative_min_contrast_noise,
          kConfigRange, "noise sigmas",
          "relative mode: the threshold is at least this many sigmas of the pixel noise (from neighbouring-pixel "
          "differences) above the background level");
  th.real("thermal_relative_min_core", &ThermalSegmenterConfig::relative_min_core, kConfigRange, "",
          "relative mode: the warmest 1 % of a person region's pixels (the skin) reach this fraction of the way "
          "from the background level to the warm tail, or to the warmest person-shaped region's if that is lower; "
          "a reflection of people in a glossy wall or a patch the day warmed stays below; 0 = off");
  th.integer("thermal_background_step_px", &ThermalSegmenterConfig::background_step_px, kConfigRange, "px",
             "background level = median of every n-th pixel in x and y");
  th.integer("thermal_open_radius_px", &ThermalSegmenterConfig::open_radius_px, kConfigRange, "px",
             "morphological opening (square 2r+1) removes specks and thin bridges; 0 = none");
  th.integer("thermal_close_radius_px", &ThermalSegmenterConfig::close_radius_px, kConfigRange, "px",
             "morphological closing fills small holes and seams; 0 = none");
  th.integer("thermal_restore_px", &ThermalSegmenterConfig::restore_px, kConfigRange, "px",
             "each kept person grows back into the warm pixels connected to it, at most this many 4-neighbour steps, "
             "never into another region: the opening removes a leg's bottom rows and a far person's 1-2 px legs, "
             "where LiDAR points sit; 0 = off");
  th.integer("thermal_border_margin_px", &ThermalSegmenterConfig::border_margin_px, kConfigRange, "px",
             "a region with a pixel in the outermost n rows or columns is cut by the image border: dropped and "
             "counted, its shape says nothing and its LiDAR points would fall partly outside the image; 0 = keep them");
  th.real("thermal_camera_hfov_deg", &ThermalSegmenterConfig::camera_hfov_deg, kConfigRange, "deg",
          "horizontal field of view of the thermal images as given: with thermal_max_range_m it sets the size "
          "floor of a person region (focal length = (image width / 2) / tan(hfov / 2))", "FLIR A65: 45");
  th.real("thermal_max_range_m", &ThermalSegmenterConfig::max_range_m, kConfigRange, "m",
          "farthest person the segmenter looks for: a region smaller than a person there is not one (keep it at "
          "lidar_max_range_m: farther people are never paired)");
  th.real("thermal_min_person_height_m", &ThermalSegmenterConfig::min_person_height_m, kConfigRange, "m",
          "height of the smallest warm silhouette of a person (a small adult's head and torso: a far person's legs are "
          "thinner than the opening removes, or as cold as the ground): a region is at least focal length * this / "
          "thermal_max_range_m px tall");
  th.real("thermal_min_person_area_m2", &ThermalSegmenterConfig::min_person_area_m2, kConfigRange, "m^2",
          "area of the smallest warm silhouette of a person (an adult's head and torso side on; the whole adult "
          "shows ~0.3 m^2 side on, ~0.5 m^2 facing the camera): a region is at least (focal length / "
          "thermal_max_range_m)^2 * this px large");
  th.integer("thermal_min_area_px", &ThermalSegmenterConfig::min_area_px, kConfigRange, "px",
             "smallest person region");
  th.real("thermal_max_area_fraction", &ThermalSegmenterConfig::max_area_fraction, kConfigRange, "",
          "largest person region, as a fraction of the image");
  th.integer("thermal_min_height_px", &ThermalSegmenterConfig::min_height_px, kConfigRange, "px",
             "smallest bounding-box height of a person");
  th.real("thermal_min_aspect", &ThermalSegmenterConfig::min_aspect, kConfigRange, "",
          "bounding-box height / width at least (an animal side on is about as high as long; a person, even striding, 1.6 or more)");
  th.real("thermal_max_aspect", &ThermalSegmenterConfig::max_aspect, kConfigRange, "",
          "bounding-box height / width at most (a pole is thinner; a person side on with legs together reaches ~7)", "at least thermal_min_aspect");
  th.real("thermal_min_fill", &ThermalSegmenterConfig::min_fill, kConfigRange, "",
          "region area / bounding-box area at least");
  th.real("thermal_max_fill", &ThermalSegmenterConfig::max_fill, kConfigRange, "",
          "region area / bounding-box area at most (a warm rectangle is not a person)", "at least thermal_min_fill");
  th.real("thermal_straight_min_aspect", &ThermalSegmenterConfig::straight_min_aspect, kConfigRange, "",
          "a region at least this slender (height / width) is a post when its sides are straight (thermal_straight_ratio)");
  th.real("thermal_straight_ratio", &ThermalSegmenterConfig::straight_ratio, kConfigRange, "",
          "straight sides: the median row extent of the legs zone (10-40 % of the height) over the torso zone's "
          "(50-80 %) within [r, 1/r] and no row between shoulders and head (78-92 %) narrower than r times the torso, "
          "or at most 1/(1-r) px wide (too narrow to tell); a person has legs ~0.5-0.8 of the torso or a neck ~0.4");
  th.real("thermal_max_neck_ratio", &ThermalSegmenterConfig::max_neck_ratio, kConfigRange, "",
          "a person has a head on a neck: the narrowest row 8-22 % of a region's height from its top is at most this "
          "fraction of the median row 20-50 % from the top (people 0.2-0.6; a warm car bonnet or a pair of legs split "
          "off at the belt ~1); applied to regions less slender than thermal_straight_min_aspect; 0 = off");
  th.real("thermal_split_max_aspect", &ThermalSegmenterConfig::split_max_aspect, kConfigRange, "",
          "a region whose height / width is below this is searched for people side by side");
  th.real("thermal_head_dip_fraction", &ThermalSegmenterConfig::head_dip_fraction, kConfigRange, "",
          "such a region is cut where its top profile dips this fraction of its height between two heads; one that is "
          "no person as a whole also at half this dip, if every part of a person's size is then a person");
  th.integer("thermal_size_history", &ThermalSegmenterConfig::size_history, kConfigRange, "",
             "candidates of recent frames from which the height people have at each foot row is learned; 0 = no size check");
  th.integer("thermal_size_min_samples", &ThermalSegmenterConfig::size_min_samples, kConfigRange, "",
             "candidates seen before the size check judges");
  th.real("thermal_size_min_ratio", &ThermalSegmenterConfig::size_min_ratio, kConfigRange, "",
          "a candidate shorter than this fraction of a person's height at its foot row is not a person (an animal end on)");
}

void addLidarRows(ParameterTable<DetectionParameters>& t) {
  auto ground = t.group<LidarGroundConfig>([](DetectionParameters& p) -> LidarGroundConfig& { return p.lidar.ground; });
  auto person = t.group<LidarPersonConfig>([](DetectionParameters& p) -> LidarPersonConfig& { return p.lidar.person; });
  t.section("LiDAR person detection: ground (detectors; issue #7)");
  ground.real("lidar_max_tilt_deg", &LidarGroundConfig::max_tilt_deg, kConfigRange, "deg",
              "largest mount tilt the levelling plane may take out");
  ground.real("lidar_level_radius_m", &LidarGroundConfig::level_radius_m, kConfigRange, "m",
              "the levelling plane is fitted to the lowest points within this horizontal range");
  ground.integer("lidar_ground_sectors", &LidarGroundConfig::sectors, kConfigRange, "",
                 "azimuth sectors of the local ground (each followed outward in range bins)");
  ground.real("lidar_ground_bin_m", &LidarGroundConfig::bin_m, kConfigRange, "m", "range bin length");
  ground.real("lidar_ground_max_slope_deg", &LidarGroundConfig::max_slope_deg, kConfigRange, "deg",
              "steepest ground slope followed from bin to bin");
  ground.real("lidar_ground_max_step_m", &LidarGroundConfig::max_step_m, kConfigRange, "m",
              "height step accepted between neighbouring ground bins on top of the slope");
  ground.real("lidar_ground_tolerance_m", &LidarGroundConfig::tolerance_m, kConfigRange, "m",
              "points up to this height above the local ground are ground");
  ground.real("lidar_ground_object_spread_m", &LidarGroundConfig::object_spread_m, kConfigRange, "m",
              "a bin whose points span more than this in height holds an object: its lowest point anchors the "
              "ground only within lidar_ground_tolerance_m of the predicted ground");
  t.section("LiDAR person detection: objects and the person test (detectors; issue #7)");
  person.real("lidar_min_range_m", &LidarPersonConfig::min_range_m, kConfigRange, "m",
              "nearest person (horizontal distance of its centre)", "below lidar_max_range_m");
  person.real("lidar_max_range_m", &LidarPersonConfig::max_range_m, kConfigRange, "m",
              "farthest person (horizontal distance of its centre)");
  person.real("lidar_min_azimuth_deg", &LidarPersonConfig::min_azimuth_deg, kConfigRange, "deg",
              "bearing window of person centres (0 = LiDAR +x, positive towards +y): the camera's field "
              "of view with a margin, so the LiDAR counts only people the camera can see; the default suits a "
              "camera facing forward (+x)", "below lidar_max_azimuth_deg");
  person.real("lidar_max_azimuth_deg", &LidarPersonConfig::max_azimuth_deg, kConfigRange, "deg",
              "upper end of the bearing window");
  person.real("lidar_view_top_margin_deg", &LidarPersonConfig::view_top_margin_deg, kConfigRange, "deg",
              "an object whose highest point is within this of the top of the scan's view (its highest beam, read "
              "off the scan) may go on above it: a trunk or a post under an HDL-64E's +2 deg top beam; not a person. "
              "Half the finest beam spacing of common sensors; 0 = off");
  person.real("lidar_max_object_height_m", &LidarPersonConfig::max_object_height_m, kConfigRange, "m",
              "points higher above the local ground are ignored (canopies, roofs)");
  person.real("lidar_cluster_cell_m", &LidarPersonConfig::cluster_cell_m, kConfigRange, "m",
              "2-D grid cell joining above-ground points into objects");
  person.real("lidar_max_split_extent_m", &LidarPersonConfig::max_split_extent_m, kConfigRange, "m",
              "objects too big for one person but at most this wide and deep are searched for people close together");
  person.real("lidar_split_tolerance_m", &LidarPersonConfig::split_tolerance_m, kConfigRange, "m",
              "horizontal gap that separates people in such an object (PCL Euclidean clustering)");
  person.real("lidar_head_dip_m", &LidarPersonConfig::head_dip_m, kConfigRange, "m",
              "people touching side by side are split where the height profile across the line of sight dips "
              "this far below both heads");
  person.real("lidar_min_height_m", &LidarPersonConfig::min_height_m, kConfigRange, "m",
              "lowest top of a person above the local ground", "below lidar_max_height_m");
  person.real("lidar_max_height_m", &LidarPersonConfig::max_height_m, kConfigRange, "m",
              "highest top of a person above the local ground");
  person.real("lidar_max_bottom_m", &LidarPersonConfig::max_bottom_m, kConfigRange, "m",
              "a person's lowest point is at most this high (legs reach the ground)");
  person.real("lidar_min_width_m", &LidarPersonConfig::min_width_m, kConfigRange, "m",
              "narrowest person across the line of sight (a person side on spans 0.15-0.2 m of points; a post this "
              "narrow is caught by lidar_narrow_*)", "below lidar_max_width_m");
  person.real("lidar_max_width_m", &LidarPersonConfig::max_width_m, kConfigRange, "m",
              "widest person across the line of sight");
  person.real("lidar_max_depth_m", &LidarPersonConfig::max_depth_m, kConfigRange, "m",
              "deepest person along the line of sight");
  person.real("lidar_min_height_to_width", &LidarPersonConfig::min_height_to_width, kConfigRange, "",
              "a person's height / width at least (a bush or a vehicle is squat)");
  person.real("lidar_post_max_width_m", &LidarPersonConfig::post_max_width_m, kConfigRange, "m",
              "an object at most this wide whose legs zone is as wide as its torso zone is a post");
  person.real("lidar_post_leg_to_torso_ratio", &LidarPersonConfig::post_leg_to_torso_ratio, kConfigRange, "",
              "'as wide': width of the zone at 20-45 % of the height over the zone at 50-85 % within [r, 1/r]");
  person.real("lidar_post_max_head_ratio", &LidarPersonConfig::post_max_head_ratio, kConfigRange, "",
              "such an object is a person after all when its head zone (above 85 % of its height) is narrower than this "
              "times its torso zone (a person striding across the view, or with hidden legs); 0 = off");
  person.real("lidar_narrow_width_m", &LidarPersonConfig::narrow_width_m, kConfigRange, "m",
              "an object narrower than this (a person side on, or a thin post) is a person only when it is "
              "lidar_narrow_min_depth_m deep or shows legs narrower than its torso (lidar_narrow_leg_margin_m)");
  person.real("lidar_narrow_min_depth_m", &LidarPersonConfig::narrow_min_depth_m, kConfigRange, "m",
              "depth along the line of sight that makes a narrow object a person (a person side on shows the near arm "
              "and shoulder, 0.19-0.34 m; a post the front half of its girth)");
  person.real("lidar_narrow_leg_margin_m", &LidarPersonConfig::narrow_leg_margin_m, kConfigRange, "m",
              "or its legs zone is narrower than its torso zone by lidar_post_leg_to_torso_ratio and by this much "
              "(about one column of points at 17 m: a post's zones differ by a column at most)");
  person.real("lidar_min_person_height_m", &LidarPersonConfig::min_person_height_m, kConfigRange, "m",
              "the smallest adult looked for: a person's highest row of points is at most one row spacing (of its own "
              "rows, at its range) and lidar_ground_tolerance_m below this");
  person.real("lidar_row_gap_factor", &LidarPersonConfig::row_gap_factor, kConfigRange, "row spacings",
              "a person's lowest row is at most this many row spacings above lidar_ground_tolerance_m (legs reach the "
              "ground) and no gap between its rows is wider (one missing row passes): a car's rear slice, a bush, a "
              "bicycle or a fence does not; 0 = off (then no sampling test at all)");
  person.integer("lidar_min_points", &LidarPersonConfig::min_points, kConfigRange, "",
                 "fewest points on a person at any range");
  person.real("lidar_min_points_at_10m", &LidarPersonConfig::min_points_at_10m, kConfigRange, "",
              "fewest points on a person at 10 m, scaled with (10 m / range)^2");
}

}  // namespace

template <>
ParameterTable<DetectionParameters> makeParameterTable() {
  ParameterTable<DetectionParameters> t;
  auto raw = t.fields();
  t.section("Raw thermal input (detectors; issue #7)");
  raw.choice("thermal_input_flip", &DetectionParameters::input_flip,
             {{"none", detection::ImageFlip::kNone},
              {"vertical", detection::ImageFlip::kVertical},
              {"horizontal", detection::ImageFlip::kHorizontal},
              {"both", detection::ImageFlip::kBoth}},
             "must be none, vertical, horizontal or both",
             "flip of the raw thermal image before segmentation and calibration (FieldSAFE: see README)");
  addThermalRows(t);
  addLidarRows(t);
  return t;
}

template <>
void finishLoading(const ParameterSource&, DetectionParameters& p) {
  p.thermal.validate();  // the rules across keys (and the ranges again, from the list the rows read)
  p.lidar.validate();
}

std::string lidarWindowWarning(const detection::LidarPersonConfig& lidar, const CameraModel& camera) {
  constexpr double kSlackDeg = 10.0;
  constexpr double kDegPerRad = 180.0 / M_PI;
  // Pinhole field of view across the image rows' width (distortion changes it by a few degrees).
  const double view_deg =
      (std::atan2(camera.cx + 0.5, camera.fx) + std::atan2(camera.width - 0.5 - camera.cx, camera.fx)) * kDegPerRad;
  const double window_deg = lidar.max_azimuth_deg - lidar.min_azimuth_deg;
  if (window_deg <= view_deg + kSlackDeg) return "";
  char text[512];
  std::snprintf(text, sizeof(text),
                "the LiDAR counts people in a %.0f deg bearing window (lidar_min_azimuth_deg %.1f .. "
                "lidar_max_azimuth_deg %.1f) but the camera sees %.0f deg across: people the camera cannot "
                "see make wrong pairs; narrow the window to the camera's view with a few degrees of margin",
                window_deg, lidar.min_azimuth_deg, lidar.max_azimuth_deg, view_deg);
  return text;
}

}  // namespace thermal_lidar_calibration
