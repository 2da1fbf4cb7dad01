// Detection quality on a raw synthetic drive (issue 7, "What must hold"): the package's two
// detectors, exactly as calibrate_bag --detect runs them (PersonDetectionAdapter, default
// parameters), scored frame by frame against the drive's truth:
//   thermal  the detected mask against /truth/thermal_person_ids (the person id each pixel shows,
//            every person at any range); a person matches at IoU >= 0.5;
//   LiDAR    the detected clusters against each point's truth_id; a cluster matches a person
//            when >= 80 % of its points are that person's.
// Scored people (the "within 20 m and wholly in view"): thermal, a person whose mask
// touches no image border and is at least 66 px tall (a 1.75 m person at 20 m on the FLIR A65:
// 772 px focal length); LiDAR, a person with >= 10 points whose centre is within 20 m and inside
// the detectors' bearing window (lidar_min/max_azimuth_deg, where the camera looks). Detections
// of people who are not scored are ignored, neither right nor wrong. For the LiDAR a second
// line ("lidar 20m") also leaves out detections whose centre is beyond 20 m, where no person is
// scored (the targets are for that region); the first line counts every detection.
// Usage: score_raw_detections RAW.bag [--config PARAMS.yaml] [--explain]
//   (make_synthetic_bag --raw; the detectors' keys of PARAMS.yaml, as calibrate_bag --config
//   reads them, else the defaults; prints one line per modality; --explain first prints a line
//   per missed person and false detection, with what the detector measured there:
//   bench/detection_explain.hpp)

#include "detection_explain.hpp"

#include "thermal_lidar_calibration/app/parameters/detection_parameters.hpp"
#include "thermal_lidar_calibration/app/parameters/parameter_source.hpp"
#include "thermal_lidar_calibration/detection/detection_scoring.hpp"
#include "thermal_lidar_calibration/ros/msg_conversion.hpp"
#include "thermal_lidar_calibration/ros/person_detection_adapter.hpp"

#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/point_cloud2_iterator.h>

#include <opencv2/imgproc.hpp>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>

namespace tlc = thermal_lidar_calibration;
namespace det = tlc::detection;

namespace {

constexpr double kScoredRangeM = 20.0;
constexpr int kMinScoredHeightPx = 66;
constexpr int kMinScoredPoints = 10;

std::vector<det::TruthPerson> thermalPeople(const cv::Mat& truth) {
  std::map<int, cv::Rect> boxes;
  for (int v = 0; v < truth.rows; ++v) {
    for (int u = 0; u < truth.cols; ++u) {
      const int id = truth.at<std::uint16_t>(v, u);
      if (id == 0) continue;
      auto it = boxes.find(id);
      if (it == boxes.end()) {
        boxes[id] = cv::Rect(u, v, 1, 1);
      } else {
        it->second |= cv::Rect(u, v, 1, 1);
      }
    }
  }
  std::vector<det::TruthPerson> people;
  for (const auto& [id, box] : boxes) {
    people.push_back({static_cast<std::uint32_t>(id),
                      det::whollyInView(truth, static_cast<std::uint32_t>(id)) && box.height >= kMinScoredHeightPx});
  }
  return people;
}

std::vector<det::TruthPerson> lidarPeople(const std::vector<Eigen::Vector3f>& points,
                                          const std::vector<std::uint32_t>& truth, const tlc::DetectionParameters& p) {
  std::map<std::uint32_t, std::pair<Eigen::Vector3f, int>> sums;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (truth[i] == 0) continue;
    // try_emplace with a zero sum: a value-initialised Eigen vector is not zeroed.
    auto& s = sums.try_emplace(truth[i], Eigen::Vector3f::Zero(), 0).first->second;
    s.first += points[i];
    ++s.second;
  }
  std::vector<det::TruthPerson> people;
  for (const auto& [id, s] : sums) {
    const Eigen::Vector3f c = s.first / static_cast<float>(s.second);
    const double bearing = std::atan2(c.y(), c.x()) * 180.0 / M_PI;
    const bool scored = s.second >= kMinScoredPoints && std::hypot(c.x(), c.y()) <= kScoredRangeM &&
                        bearing >= p.lidar.person.min_azimuth_deg && bearing <= p.lidar.person.max_azimuth_deg;
    people.push_back({id, scored});
  }
  return people;
}

}  // namespace

int main(int argc, char** argv) {
  std::string bag_path, config_path;
  bool explain = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--config" && i + 1 < argc) {
      config_path = argv[++i];
    } else if (arg == "--explain") {
      explain = true;
    } else if (bag_path.empty() && arg.rfind("--", 0) != 0) {
      bag_path = arg;
    } else {
      bag_path.clear();
      break;
    }
  }
  if (bag_path.empty()) {
    std::fprintf(stderr, "usage: score_raw_detections RAW.bag [--config PARAMS.yaml] [--explain]\n");
    return 2;
  }
  try {
    const tlc::DetectionParameters params = config_path.empty()
                                                ? tlc::DetectionParameters{}
                                                : tlc::loadDetectionParameters(*tlc::makeYamlParameterSource(config_path));
    tlc::ros_io::PersonDetectionAdapter adapter(params);
    rosbag::Bag bag(bag_path, rosbag::bagmode::Read);
    det::DetectionScore thermal, lidar, lidar_near;
    sensor_msgs::Image::ConstPtr image, mask;
    for (const rosbag::MessageInstance& m :
         rosbag::View(bag, rosbag::TopicQuery({"/thermal/image_raw", "/truth/thermal_person_ids", "/lidar/points"}))) {
      if (m.getTopic() == "/lidar/points") {
        const auto cloud = m.instantiate<sensor_msgs::PointCloud2>();
        const tlc::ros_io::DetectedCloud out = adapter.detect(*cloud, m.getTopic());
        const std::vector<Eigen::Vector3f> points = tlc::ros_io::decodeCloudPoints(*cloud, m.getTopic(), 1u << 30);
        std::vector<std::uint32_t> truth;
        for (sensor_msgs::PointCloud2ConstIterator<std::uint32_t> id(*cloud, "truth_id"); id != id.end(); ++id) {
          truth.push_back(*id);
        }
        std::vector<std::uint32_t> detected_truth;
        for (int index : out.detection.indices) detected_truth.push_back(truth[static_cast<std::size_t>(index)]);
        const std::vector<det::TruthPerson> people = lidarPeople(points, truth, params);
        const det::FrameScore frame = det::scoreClusters(out.detection.labels, detected_truth, people);
        lidar.add(frame);
        if (explain) tlc::bench::explainLidar(stdout, cloud->header.stamp.toSec(), out.detection, frame, points, truth);
        std::vector<std::uint32_t> near_labels, near_truth;
        for (std::size_t k = 0; k < out.detection.labels.size(); ++k) {
          const std::uint32_t label = out.detection.labels[k];
          if (out.detection.people[label - 1].range_m > kScoredRangeM) continue;
          near_labels.push_back(label);
          near_truth.push_back(detected_truth[k]);
        }
        lidar_near.add(det::scoreClusters(near_labels, near_truth, people));
        continue;
      }
      if (m.getTopic() == "/thermal/image_raw") image = m.instantiate<sensor_msgs::Image>();
      if (m.getTopic() == "/truth/thermal_person_ids") mask = m.instantiate<sensor_msgs::Image>();
      if (!image || !mask || image->header.stamp != mask->header.stamp) continue;
      const tlc::ros_io::SegmentedImage seg = adapter.segment(image, "/thermal/image_raw");
      const cv::Mat truth = tlc::ros_io::decodeMonoImage(*mask, "/truth/thermal_person_ids");
      const cv::Mat detected = tlc::ros_io::decodeMonoImage(*seg.mask, "mask");
      const det::FrameScore frame = det::scoreMask(detected, truth, thermalPeople(truth));
      thermal.add(frame);
      if (explain) tlc::bench::explainThermal(stdout, image->header.stamp.toSec(), seg.segmentation, frame, detected, truth);
      image.reset();
      mask.reset();
    }
    const auto print = [](const char* name, const det::DetectionScore& s) {
      std::printf("%-9s frames %5ld  recall %.3f  precision %.3f  counts agree %.3f  (TP %ld, FP %ld, FN %ld, ignored %ld)\n",
                  name, s.frames, s.recall(), s.precision(), s.countAgreement(), s.true_positives, s.false_positives,
                  s.false_negatives, s.ignored);
    };
    print("thermal", thermal);
    print("lidar", lidar);
    print("lidar 20m", lidar_near);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "score_raw_detections: error: %s\n", e.what());
    return 1;
  }
}
