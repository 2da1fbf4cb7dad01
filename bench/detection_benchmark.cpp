// Speed of the person detectors on one core (Google Benchmark; not a test):
//   BM_ThermalSegmentation  one 640x512 frame: 16-bit radiometric (the default) and 8-bit
//                           relative; budget 3 ms (issue #7);
//   BM_LidarDetection       one full HDL-32E scan (~69k points: rolling field, tilted mount,
//                           people, posts, bushes, a parked vehicle, a hedge, a shed and tree
//                           lines, ray cast with the synthetic rig's beam model and solids);
//                           budget 25 ms;
//   BM_TextbookPclPipeline  for comparison on the same scan: VoxelGrid 0.1 m, one RANSAC plane,
//                           EuclideanClusterExtraction 0.4 m (NOTES.md's "textbook" pipeline).
// Run: scripts/benchmark.sh --benchmark_filter='Thermal|Lidar|Textbook' (OpenCV is set to one
// thread here; PCL and the detector use one).
#include "thermal_lidar_calibration/detection/lidar_person_detector.hpp"
#include "thermal_lidar_calibration/detection/person_size_model.hpp"
#include "thermal_lidar_calibration/detection/thermal_person_segmenter.hpp"

#include "../test/support/lidar_scene.hpp"
#include "../test/support/thermal_scene.hpp"

#include <benchmark/benchmark.h>
#include <opencv2/core/utility.hpp>
#include <pcl/filters/voxel_grid.h>
#include <pcl/point_types.h>
#include <pcl/sample_consensus/method_types.h>
#include <pcl/sample_consensus/model_types.h>
#include <pcl/search/kdtree.h>
#include <pcl/segmentation/extract_clusters.h>
#include <pcl/segmentation/sac_segmentation.h>

using namespace thermal_lidar_calibration;

namespace {

// A field at dusk seen by a FLIR A65-sized camera: cold sky above the horizon, ground warming
// towards the bottom, three people (one far), an animal, an engine and a sun-heated post.
cv::Mat benchFrame16() {
  cv::Mat image = test_support::thermalBackground(cv::Size(640, 512), 283.0, 0.08, 11);
  test_support::fillKelvin(image, cv::Rect(0, 0, 640, 180), 262.0);  // sky
  for (int y = 180; y < 512; y += 8) test_support::fillKelvin(image, cv::Rect(0, y, 640, 8), 283.0 + 0.02 * (y - 180));
  cv::Mat noise(image.size(), CV_16SC1);
  cv::randn(noise, 0, 2);  // 0.08 K
  cv::add(image, noise, image, cv::noArray(), CV_16U);
  test_support::drawPerson(image, 140, 150, 190, 307.0, 301.0);
  test_support::drawPerson(image, 330, 200, 110, 306.0, 298.0);
  test_support::drawPerson(image, 520, 190, 45, 306.0, 299.0);
  test_support::drawAnimal(image, 430, 330, 80, 308.0);
  test_support::fillKelvin(image, cv::Rect(40, 380, 90, 40), 340.0);
  test_support::fillKelvin(image, cv::Rect(600, 120, 6, 140), 300.0);
  return image;
}

void BM_ThermalSegmentation(benchmark::State& state) {
  cv::setNumThreads(1);
  const bool eight_bit = state.range(0) != 0;
  cv::Mat image = benchFrame16();
  // 8-bit: 260-320 K mapped linearly to 0-255, as a camera's fixed-range video output.
  const double per_count = 255.0 / ((320.0 - 260.0) / test_support::kKelvinPerCount);
  if (eight_bit) image.convertTo(image, CV_8U, per_count, -260.0 / test_support::kKelvinPerCount * per_count);
  const detection::ThermalPersonSegmenter segmenter;
  std::size_t people = 0;
  for (auto _ : state) {
    const auto result = segmenter.segment(image);
    people = result.people.size();
    benchmark::DoNotOptimize(result.mask.data);
  }
  state.counters["people"] = static_cast<double>(people);
  state.SetLabel(eight_bit ? "640x512 8-bit, relative" : "640x512 16-bit, radiometric");
}
BENCHMARK(BM_ThermalSegmentation)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// The ground-plane size check after segmentation, per frame: a full history (300 candidates)
// and its refit every 5th frame included, as the live segmenter and calibrate_bag --detect run it.
void BM_ThermalSizeCheck(benchmark::State& state) {
  const detection::ThermalSegmentation frame = detection::ThermalPersonSegmenter().segment(benchFrame16());
  detection::PersonSizeModel model;
  for (int k = 0; k < 200; ++k) {
    detection::ThermalSegmentation copy = frame;
    detection::applySizeCheck(copy, model);
  }
  for (auto _ : state) {
    // The mask's pixels are shared with `frame`, not copied (a copy would cost more than the
    // check): a drop relabels them in place, which the check, working on boxes, never reads.
    detection::ThermalSegmentation copy = frame;
    detection::applySizeCheck(copy, model);
    benchmark::DoNotOptimize(copy.people.data());
  }
  state.counters["ready"] = model.fit() ? 1 : 0;
  state.SetLabel("3 candidates per frame, 300 remembered");
}
BENCHMARK(BM_ThermalSizeCheck)->Unit(benchmark::kMicrosecond);

const test_support::CraftedScan& benchScan() {
  static const test_support::CraftedScan scan = [] {
    using namespace test_support;
    const Terrain field = Terrain::rolling(0.3);
    Mount mount;
    mount.pitch_deg = 2.0;
    mount.roll_deg = -1.0;
    std::vector<SceneObject> objects = {
        personAt(field, 7.0, 1.5, 1), personAt(field, 11.0, -2.5, 2, 1.65, 1.0, 0.35, 0.7),
        personAt(field, 11.2, -1.9, 3, 1.8), personAt(field, 17.0, 5.0, 4, 1.7, 2.5, 0.3, 2.0),
        personAt(field, -9.0, 4.0, 5), postAt(field, 9.0, 3.0, 1.6, 0.12), postAt(field, 14.0, -6.0, 2.5, 0.07),
        bushAt(field, 12.0, 6.0, Eigen::Vector3d(0.7, 0.6, 0.8)), bushAt(field, -5.0, -7.0, Eigen::Vector3d(1.2, 1.0, 0.9)),
        blobAt(field, 4.0, -9.0, 0.9, Eigen::Vector3d(2.3, 1.0, 0.8), 0.4),        // parked vehicle
        blobAt(field, 0.0, 22.0, 1.5, Eigen::Vector3d(25.0, 1.2, 1.8)),             // hedge row
        blobAt(field, -18.0, -12.0, 2.5, Eigen::Vector3d(5.0, 4.0, 3.5), 0.3),      // shed
        blobAt(field, 25.0, -15.0, 5.0, Eigen::Vector3d(3.0, 3.0, 3.5)),            // tree crown
        // Tree lines around the field, 36-42 m away and ~12 m high: the upper beams return
        // too, as in a real scan (~69k of the 32 x 2170 beams).
        blobAt(field, 42.0, 0.0, 4.0, Eigen::Vector3d(4.0, 60.0, 8.0)), blobAt(field, -40.0, 0.0, 4.0, Eigen::Vector3d(4.0, 60.0, 8.0)),
        blobAt(field, 0.0, 38.0, 4.0, Eigen::Vector3d(60.0, 4.0, 8.0)), blobAt(field, 0.0, -36.0, 4.0, Eigen::Vector3d(60.0, 4.0, 8.0)),
    };
    return castScan(synthetic::LidarModel::hdl32e(), field, mount, objects, 0.02, 2024);
  }();
  return scan;
}

void BM_LidarDetection(benchmark::State& state) {
  const auto& scan = benchScan();
  detection::LidarPersonDetector detector;
  std::size_t people = 0;
  for (auto _ : state) {
    const auto result = detector.detect(scan.points);
    people = result.people.size();
    benchmark::DoNotOptimize(result.points.data());
  }
  state.counters["points"] = static_cast<double>(scan.points.size());
  state.counters["people"] = static_cast<double>(people);
  state.SetLabel("HDL-32E scan, rolling field, 5 people among clutter");
}
BENCHMARK(BM_LidarDetection)->Unit(benchmark::kMillisecond);

void BM_TextbookPclPipeline(benchmark::State& state) {
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  for (const auto& p : benchScan().points) cloud->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
  std::size_t clusters = 0;
  for (auto _ : state) {
    pcl::PointCloud<pcl::PointXYZ>::Ptr voxels(new pcl::PointCloud<pcl::PointXYZ>);
    pcl::VoxelGrid<pcl::PointXYZ> grid;
    grid.setInputCloud(cloud);
    grid.setLeafSize(0.1f, 0.1f, 0.1f);
    grid.filter(*voxels);
    pcl::SACSegmentation<pcl::PointXYZ> sac;
    sac.setModelType(pcl::SACMODEL_PLANE);
    sac.setMethodType(pcl::SAC_RANSAC);
    sac.setDistanceThreshold(0.15);
    sac.setInputCloud(voxels);
    pcl::PointIndices ground;
    pcl::ModelCoefficients plane;
    sac.segment(ground, plane);
    std::vector<bool> is_ground(voxels->size(), false);
    for (int i : ground.indices) is_ground[i] = true;
    pcl::PointCloud<pcl::PointXYZ>::Ptr rest(new pcl::PointCloud<pcl::PointXYZ>);
    for (std::size_t i = 0; i < voxels->size(); ++i) {
      if (!is_ground[i]) rest->push_back((*voxels)[i]);
    }
    pcl::search::KdTree<pcl::PointXYZ>::Ptr tree(new pcl::search::KdTree<pcl::PointXYZ>);
    tree->setInputCloud(rest);
    pcl::EuclideanClusterExtraction<pcl::PointXYZ> ece;
    ece.setClusterTolerance(0.4);
    ece.setMinClusterSize(5);
    ece.setSearchMethod(tree);
    ece.setInputCloud(rest);
    std::vector<pcl::PointIndices> found;
    ece.extract(found);
    clusters = found.size();
  }
  state.counters["points"] = static_cast<double>(cloud->size());
  state.counters["clusters"] = static_cast<double>(clusters);
  state.SetLabel("VoxelGrid 0.1 + RANSAC plane + Euclidean 0.4 (no person filter)");
}
BENCHMARK(BM_TextbookPclPipeline)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
