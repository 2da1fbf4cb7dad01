// How often association pairs a LiDAR person with the wrong mask region (issue 23, "What must
// hold": at most 1 % of associated persons), on a raw synthetic drive whose truth says who is who:
// the raw points carry each point's truth_id, /truth/thermal_person_ids the person each pixel
// shows. The package's detectors run on each frame exactly as calibrate_bag --detect runs them;
// the frames the result file lists as association pairs are associated again at the result's
// extrinsic (the set the last round paired, when the rounds converged), and each match is scored:
//   right  the cluster's points and the region's pixels are mostly the same person;
//   wrong  different people, or a person matched to something that is not one (a warm post);
//   both   neither is a person (a confounder both detectors took for one): no person mismatched.
// Points stay where they were captured (the drives measured have no camera time offset).
// Usage: score_association RAW.bag --result RESULT.yaml [--config PARAMS.yaml]

#include "thermal_lidar_calibration/app/parameters/detection_parameters.hpp"
#include "thermal_lidar_calibration/app/parameters/parameter_source.hpp"
#include "thermal_lidar_calibration/app/parameters/core_parameters.hpp"
#include "thermal_lidar_calibration/app/files/result_file.hpp"
#include "thermal_lidar_calibration/app/files/yaml_file.hpp"
#include "thermal_lidar_calibration/core/person_association.hpp"
#include "thermal_lidar_calibration/ros/msg_conversion.hpp"
#include "thermal_lidar_calibration/ros/person_detection_adapter.hpp"

#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/point_cloud2_iterator.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <string>

namespace tlc = thermal_lidar_calibration;

namespace {

// The stamps (ns) of the result's association pairs.
std::set<std::int64_t> associationStamps(const std::string& result) {
  const YAML::Node root = tlc::loadYamlFile(result, "result file");
  std::set<std::int64_t> stamps;
  for (const YAML::Node& pair : root["pairs"]) {
    if (pair["rule"] && pair["rule"].as<std::string>() == "association") {
      stamps.insert(std::llround(pair["stamp"].as<double>() * 1e9));
    }
  }
  return stamps;
}

template <typename Map>
std::uint32_t majority(const Map& votes) {
  std::uint32_t best = 0;
  int most = 0;
  for (const auto& [id, n] : votes) {
    if (n > most) {
      most = n;
      best = id;
    }
  }
  return best;
}

constexpr std::int64_t kSlopNs = 60000000;   // sync_slop's default, 0.05 s, and the stamps' rounding
constexpr std::int64_t kStampNs = 6000000;   // half the result file's stamp resolution, and some

struct Detected {
  std::vector<Eigen::Vector3f> points;
  std::vector<std::int32_t> labels;
  std::vector<std::uint32_t> truth;
};

}  // namespace

int main(int argc, char** argv) {
  std::string bag_path, result_path, config_path;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string arg = argv[i];
    if (arg == "--result") result_path = argv[i + 1];
    if (arg == "--config") config_path = argv[i + 1];
    if (arg == "--bag") bag_path = argv[i + 1];
  }
  if (bag_path.empty() || result_path.empty()) {
    std::fprintf(stderr, "usage: score_association --bag RAW.bag --result RESULT.yaml [--config PARAMS.yaml]\n");
    return 2;
  }
  try {
    const tlc::DetectionParameters detection = config_path.empty()
        ? tlc::DetectionParameters{} : tlc::loadDetectionParameters(*tlc::makeYamlParameterSource(config_path));
    const tlc::CoreParameters core = config_path.empty()
        ? tlc::CoreParameters{} : tlc::loadCoreParameters(*tlc::makeYamlParameterSource(config_path));
    tlc::AssociationConfig config = core.pairing.association;
    config.min_points_in_view = core.gate.min_points_per_cluster;
    const tlc::Extrinsic extrinsic = tlc::readExtrinsicFile(result_path);
    const std::set<std::int64_t> wanted = associationStamps(result_path);
    tlc::ros_io::PersonDetectionAdapter adapter(detection);
    rosbag::Bag bag(bag_path, rosbag::bagmode::Read);
    tlc::CameraModel camera;
    bool have_camera = false;
    std::map<std::int64_t, Detected> clouds;
    std::map<std::int64_t, cv::Mat> masks, truths;
    long frames = 0, persons = 0, right = 0, wrong = 0, both_not_person = 0;
    for (const rosbag::MessageInstance& m : rosbag::View(
             bag, rosbag::TopicQuery({"/thermal/camera_info", "/thermal/image_raw", "/truth/thermal_person_ids",
                                      "/lidar/points"}))) {
      if (m.getTopic() == "/thermal/camera_info") {
        if (!have_camera) camera = tlc::ros_io::cameraModelFromMsg(*m.instantiate<sensor_msgs::CameraInfo>());
        have_camera = true;
        continue;
      }
      std::int64_t stamp = 0;
      if (m.getTopic() == "/lidar/points") {
        const auto cloud = m.instantiate<sensor_msgs::PointCloud2>();
        stamp = static_cast<std::int64_t>(cloud->header.stamp.toNSec());
        // The cloud a pair's image was synchronized with: the nearest within the sync slop.
        const auto near = wanted.lower_bound(stamp - kSlopNs);
        if (near == wanted.end() || *near > stamp + kSlopNs) continue;
        const tlc::ros_io::DetectedCloud out = adapter.detect(*cloud, m.getTopic());
        // Every point of the scan, in its order (the detection's indices count them all).
        std::vector<Eigen::Vector3f> points;
        for (sensor_msgs::PointCloud2ConstIterator<float> p(*cloud, "x"); p != p.end(); ++p) {
          points.emplace_back(p[0], p[1], p[2]);
        }
        std::vector<std::uint32_t> truth;
        for (sensor_msgs::PointCloud2ConstIterator<std::uint32_t> id(*cloud, "truth_id"); id != id.end(); ++id) {
          truth.push_back(*id);
        }
        Detected d;
        for (std::size_t k = 0; k < out.detection.indices.size(); ++k) {
          const std::size_t index = static_cast<std::size_t>(out.detection.indices[k]);
          d.points.push_back(points[index]);
          d.labels.push_back(static_cast<std::int32_t>(out.detection.labels[k]));
          d.truth.push_back(truth[index]);
        }
        clouds[stamp] = std::move(d);
      } else {
        const auto image = m.instantiate<sensor_msgs::Image>();
        stamp = static_cast<std::int64_t>(image->header.stamp.toNSec());
        // The result file writes stamps to 12 significant digits (10 ms at today's epoch).
        const auto listed = wanted.lower_bound(stamp - kStampNs);
        if (listed == wanted.end() || *listed > stamp + kStampNs) continue;
        if (m.getTopic() == "/truth/thermal_person_ids") {
          truths[stamp] = tlc::ros_io::decodeMonoImage(*image, m.getTopic()).clone();
        } else {
          const tlc::ros_io::SegmentedImage seg = adapter.segment(image, m.getTopic());
          masks[stamp] = tlc::ros_io::decodeMonoImage(*seg.mask, "mask").clone();
        }
      }
    }
    for (const auto& [stamp, mask] : masks) {
      if (!truths.count(stamp) || !have_camera) continue;
      // The nearest cloud.
      auto best = clouds.end();
      for (auto it = clouds.lower_bound(stamp - kSlopNs); it != clouds.end() && it->first <= stamp + kSlopNs; ++it) {
        if (best == clouds.end() || std::llabs(it->first - stamp) < std::llabs(best->first - stamp)) best = it;
      }
      if (best == clouds.end()) continue;
      const Detected& d = best->second;
      const cv::Mat regions = tlc::personRegions(mask);
      const cv::Mat& truth = truths[stamp];
      const tlc::FrameAssociation a = tlc::associateClusters(camera, regions, d.points, d.labels, extrinsic, config);
      ++frames;
      for (const tlc::ClusterMatch& match : a.matches) {
        std::map<std::uint32_t, int> cluster_votes, region_votes;
        for (std::size_t i = 0; i < d.labels.size(); ++i) {
          if (d.labels[i] == match.label) ++cluster_votes[d.truth[i]];
        }
        for (int v = 0; v < regions.rows; ++v) {
          for (int u = 0; u < regions.cols; ++u) {
            if (regions.at<std::uint16_t>(v, u) == match.region) ++region_votes[truth.at<std::uint16_t>(v, u)];
          }
        }
        const std::uint32_t who_lidar = majority(cluster_votes), who_camera = majority(region_votes);
        if (who_lidar == 0 && who_camera == 0) {
          ++both_not_person;
          continue;
        }
        ++persons;
        if (who_lidar == who_camera) {
          ++right;
        } else {
          ++wrong;
          std::printf("wrong: stamp %.3f cluster %d (truth %u) -> region %d (truth %u), overlap %.2f second %.2f\n",
                      stamp * 1e-9, match.label, who_lidar, match.region, who_camera, match.overlap, match.second);
        }
      }
    }
    std::printf("association pairs %ld of %zu listed | persons matched %ld: right %ld, wrong %ld (%.2f %%) | "
                "non-person matched to non-person %ld\n",
                frames, wanted.size(), persons, right, wrong, persons > 0 ? 100.0 * wrong / persons : 0.0,
                both_not_person);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "score_association: error: %s\n", e.what());
    return 1;
  }
}
