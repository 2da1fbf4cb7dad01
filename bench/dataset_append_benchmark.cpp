// The cost of appending one kept pair to the node's dataset bag (~dataset_bag) when the bag
// already holds N pairs (Google Benchmark; not a test). Issue 12 asks that an append cost the
// same at pair 500 as at pair 5. Counter bytes_per_append: how much one append adds to the file.
// Run: scripts/benchmark.sh (builds Release, then runs the benchmarks).
#include "thermal_lidar_calibration/ros/dataset_bag.hpp"

#include "../test/support/dataset_pair_messages.hpp"

#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

namespace tlc = thermal_lidar_calibration;

namespace {

// A few distinct pairs, reused: making a noise image costs more than appending it.
const std::vector<tlc::test_support::PairMessages>& pairs() {
  static const auto made = [] {
    std::vector<tlc::test_support::PairMessages> out;
    for (unsigned i = 0; i < 8; ++i) out.push_back(tlc::test_support::makePairMessages(100.0 + i, i));
    return out;
  }();
  return made;
}

void append(tlc::ros_io::DatasetBagWriter& writer, std::size_t i) {
  tlc::test_support::PairMessages m = pairs()[i % pairs().size()];
  const ros::Time t(100.0 + 0.1 * static_cast<double>(i));
  m.image.header.stamp = m.mask.header.stamp = m.clusters.header.stamp = t;
  writer.write(m.image, m.mask, m.clusters, m.info);
}

void BM_DatasetAppend(benchmark::State& state) {
  const std::size_t held = static_cast<std::size_t>(state.range(0));
  const char* base = std::getenv("TLC_BENCH_DIR");
  const std::filesystem::path dir =
      std::filesystem::path(base ? base : "/tmp") / ("tlc_append_bench_" + std::to_string(held));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "dataset.bag").string();
  tlc::ros_io::DatasetBagWriter writer(path, false);
  std::size_t i = 0;
  for (; i < held; ++i) append(writer, i);
  const auto size_before = std::filesystem::file_size(path);
  for (auto _ : state) append(writer, i++);
  const double appended = static_cast<double>(i - held);
  state.counters["bytes_per_append"] =
      static_cast<double>(std::filesystem::file_size(path) - size_before) / appended;
  state.SetLabel("bag held " + std::to_string(held) + " pairs");
  std::filesystem::remove_all(dir);
}
BENCHMARK(BM_DatasetAppend)->Arg(5)->Arg(100)->Arg(500)->Iterations(30)
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
