// The cost of reading per-point times (issue 21) where clouds arrive at sensor rate (Google
// Benchmark; not a test): the clusters of a frame decoded with and without their `time` field,
// and a raw HDL-32E-sized scan decoded for the person detector (points and their indices) and
// its person points re-encoded with the scan's other fields. Run: scripts/benchmark.sh.
#include "thermal_lidar_calibration/ros/msg_conversion.hpp"
#include "thermal_lidar_calibration/ros/person_detection_adapter.hpp"

#include <benchmark/benchmark.h>
#include <sensor_msgs/point_cloud2_iterator.h>

#include <numeric>
#include <vector>

namespace tlc = thermal_lidar_calibration;

namespace {

// velodyne_pointcloud's XYZIRT layout (+ label for clusters), n points spread over a sweep.
sensor_msgs::PointCloud2 velodyneCloud(std::size_t n, bool label) {
  sensor_msgs::PointCloud2 cloud;
  cloud.header.stamp = ros::Time(1600000000.0);
  sensor_msgs::PointCloud2Modifier modifier(cloud);
  if (label) {
    modifier.setPointCloud2Fields(7, "x", 1, sensor_msgs::PointField::FLOAT32, "y", 1, sensor_msgs::PointField::FLOAT32,
                                  "z", 1, sensor_msgs::PointField::FLOAT32, "intensity", 1,
                                  sensor_msgs::PointField::FLOAT32, "ring", 1, sensor_msgs::PointField::UINT16, "time",
                                  1, sensor_msgs::PointField::FLOAT32, "label", 1, sensor_msgs::PointField::UINT32);
  } else {
    modifier.setPointCloud2Fields(6, "x", 1, sensor_msgs::PointField::FLOAT32, "y", 1, sensor_msgs::PointField::FLOAT32,
                                  "z", 1, sensor_msgs::PointField::FLOAT32, "intensity", 1,
                                  sensor_msgs::PointField::FLOAT32, "ring", 1, sensor_msgs::PointField::UINT16, "time",
                                  1, sensor_msgs::PointField::FLOAT32);
  }
  modifier.resize(n);
  sensor_msgs::PointCloud2Iterator<float> x(cloud, "x"), y(cloud, "y"), z(cloud, "z"), t(cloud, "time");
  for (std::size_t i = 0; i < n; ++i, ++x, ++y, ++z, ++t) {
    *x = 10.0f + 0.001f * static_cast<float>(i % 997);
    *y = 0.002f * static_cast<float>(i % 499);
    *z = -1.0f + 0.001f * static_cast<float>(i % 1999);
    *t = -0.1f + 0.1f * static_cast<float>(i) / static_cast<float>(n);
  }
  if (label) {
    sensor_msgs::PointCloud2Iterator<std::uint32_t> l(cloud, "label");
    for (std::size_t i = 0; i < n; ++i, ++l) *l = 1 + static_cast<std::uint32_t>(i % 3);
  }
  return cloud;
}

void BM_DecodeClusters(benchmark::State& state) {
  const sensor_msgs::PointCloud2 cloud = velodyneCloud(static_cast<std::size_t>(state.range(0)), true);
  const tlc::PointTimeField field = tlc::PointTimeField::parse(state.range(1) ? "auto" : "none");
  for (auto _ : state) benchmark::DoNotOptimize(tlc::ros_io::decodeClusters(cloud, "/c", field));
  state.SetItemsProcessed(state.iterations() * state.range(0));
  state.SetLabel(state.range(1) ? "with times" : "times ignored");
}
BENCHMARK(BM_DecodeClusters)->Args({2000, 0})->Args({2000, 1})->Unit(benchmark::kMicrosecond);

// What the detector adapter does besides detecting: every point of a 70k-point scan decoded with
// its index, and 2000 person points encoded with the scan's intensity, ring and time.
void BM_RawScanDecodeAndCarry(benchmark::State& state) {
  const sensor_msgs::PointCloud2 scan = velodyneCloud(70000, false);
  std::vector<std::uint32_t> person(2000);
  std::iota(person.begin(), person.end(), 30000u);
  for (auto _ : state) {
    const tlc::ros_io::DecodedCloud decoded = tlc::ros_io::decodeCloud(scan, "/lidar/points");
    const std::vector<Eigen::Vector3f> points(decoded.points.begin() + 30000, decoded.points.begin() + 32000);
    const std::vector<std::uint32_t> labels(points.size(), 1);
    benchmark::DoNotOptimize(tlc::ros_io::encodeLabelledPoints(points, labels, scan, person));
  }
}
BENCHMARK(BM_RawScanDecodeAndCarry)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
