#include "thermal_lidar_calibration/detection_tool/detect_people.hpp"

#include "thermal_lidar_calibration/app/parameters/detection_parameters.hpp"
#include "thermal_lidar_calibration/app/parameters/parameter_source.hpp"
#include "thermal_lidar_calibration/detection/lidar_person_detector.hpp"
#include "thermal_lidar_calibration/detection/thermal_person_segmenter.hpp"
#include "thermal_lidar_calibration/detection_tool/detection_files.hpp"
#include "thermal_lidar_calibration/detection/detection_views.hpp"

#include <cmath>
#include <iomanip>
#include <sstream>

namespace thermal_lidar_calibration {
namespace detection_tool {
namespace {

void segmentImage(const DetectPeopleOptions& o, const DetectionParameters& params, std::ostream& out,
                  std::ostream& err) {
  detection::ThermalSegmenterConfig config = params.thermal;
  if (o.kelvin_per_count) config.kelvin_per_count = *o.kelvin_per_count;
  if (o.kelvin_offset) config.kelvin_offset = *o.kelvin_offset;
  const detection::ThermalPersonSegmenter segmenter(config);  // validates
  const cv::Mat image = detection::flipImage(readThermalImage(o.image), o.flip);
  const detection::ThermalSegmentation result = segmenter.segment(image);
  writeMask(o.mask_out, result.mask);
  if (!o.overlay_out.empty()) writeImage(o.overlay_out, detection::renderMaskOverlay(image, result));
  for (const auto& p : result.people) {
    out << "person " << p.id << " bbox " << p.bbox.x << ' ' << p.bbox.y << ' ' << p.bbox.width << ' '
        << p.bbox.height << " area " << p.area_px << '\n';
  }
  if (result.people.empty()) out << "no person found\n";
  if (result.border_cut > 0) out << "cut by the image border: " << result.border_cut << " (not reported)\n";
  if (o.explain) {
    err << std::fixed << std::setprecision(2) << (result.radiometric ? "radiometric" : "relative")
        << ": background " << result.background_level << ", person band [" << result.threshold_low << ", "
        << result.threshold_high << "]" << (result.radiometric ? " K" : "") << "; " << result.components
        << " warm regions; a person is at least " << result.min_height_px << " px tall and "
        << result.min_area_px << " px large";
    if (result.core_threshold > 0) err << "; its warm core reaches " << result.core_threshold;
    err << '\n';
    for (const auto& p : result.people) {
      err << "person " << p.id << ": fill " << p.fill << ", legs/torso " << p.leg_to_torso_width << ", mean level "
          << p.mean_level << '\n';
    }
    for (const auto& r : result.rejected) {
      err << "not a person (" << r.reason << "): bbox " << r.bbox.x << ' ' << r.bbox.y << ' ' << r.bbox.width << ' '
          << r.bbox.height << " area " << r.area_px << '\n';
    }
  }
}

void detectInCloud(const DetectPeopleOptions& o, const DetectionParameters& params, std::ostream& out,
                   std::ostream& err) {
  detection::LidarPersonDetector detector(params.lidar);  // validates
  const CloudFile cloud = readCloud(o.cloud);
  const detection::LidarDetection result = detector.detect(cloud.points);
  writeLabelledCloud(o.clusters_out, result.points, result.labels);
  if (!o.view_out.empty()) {
    writeImage(o.view_out, detection::renderBirdsEye(cloud.points, result, detector, params.lidar.person.max_range_m));
  }
  out << std::fixed << std::setprecision(3);
  for (const auto& p : result.people) {
    out << "person " << p.label << " centroid " << p.centroid.x() << ' ' << p.centroid.y() << ' ' << p.centroid.z()
        << " size " << p.size.x() << ' ' << p.size.y() << ' ' << p.size.z() << " points " << p.point_count << '\n';
  }
  if (result.people.empty()) out << "no person found\n";
  if (o.explain) {
    err << std::fixed << std::setprecision(2) << "ground: tilt " << result.tilt_deg << " deg, sensor "
        << result.sensor_height_m << " m above it; " << result.objects << " objects above the ground; ";
    if (result.view_top_found) {
      err << "top of the view " << result.view_top_elevation_deg << " deg (origin " << result.view_top_offset_m
          << " m up)\n";
    } else {
      err << "no top of the view in the scan\n";
    }
    const auto describe = [&](const detection::PersonShape& s) {
      err << "range " << s.range_m << " m, height " << s.top_m << " m, lowest " << s.bottom_m << " m, width "
          << s.width_m << " m, depth " << s.depth_m << " m, legs/torso " << s.leg_to_torso_width << ", points "
          << s.points;
      if (std::isfinite(s.view_top_gap_deg)) err << ", " << s.view_top_gap_deg << " deg below the view's top";
      err << '\n';
    };
    for (const auto& p : result.people) {
      err << "person " << p.label << ": ";
      describe(p.shape);
    }
    for (const auto& r : result.rejected) {
      if (r.shape.top_m < params.lidar.person.min_height_m) continue;  // only the person-high ones
      err << "not a person (" << detection::toString(r.verdict) << "): ";
      describe(r.shape);
    }
  }
}

}  // namespace

void runDetectPeople(const DetectPeopleOptions& o, std::ostream& out, std::ostream& err) {
  // --config: the flat keys of config/default.yaml; a partial file overrides only what it names
  // (keys of the calibration itself are ignored here).
  const DetectionParameters params =
      o.config.empty() ? DetectionParameters{} : loadDetectionParameters(*makeYamlParameterSource(o.config));
  if (!o.image.empty()) {
    segmentImage(o, params, out, err);
  } else {
    detectInCloud(o, params, out, err);
  }
}

int detectPeopleMain(int argc, char** argv, std::ostream& out, std::ostream& err) {
  std::optional<DetectPeopleOptions> options;
  try {
    options = parseDetectPeopleArgs(std::vector<std::string>(argv + 1, argv + argc));
  } catch (const UsageError& e) {
    err << "detect_people: " << e.what() << '\n' << detectPeopleUsage();
    return 2;
  }
  if (!options) {
    out << detectPeopleUsage();
    return 0;
  }
  try {
    runDetectPeople(*options, out, err);
  } catch (const std::invalid_argument& e) {
    err << "detect_people: " << e.what() << '\n';
    return 1;
  } catch (const std::exception& e) {  // e.g. std::bad_alloc on an absurd file, cv::Exception
    err << "detect_people: " << e.what() << '\n';
    return 1;
  }
  return 0;
}

}  // namespace detection_tool
}  // namespace thermal_lidar_calibration
