#!/usr/bin/env bash
# Re-measures the speed figures of the README: loss throughput per core, the whole default run
# (Algorithm 2 at Table 1 + refinement) on 60 pairs of ~100 points with 2 threads, the quality
# assessment after it, appending a kept pair to the dataset bag at 5, 100 and 500 pairs, and the
# person detectors (thermal segmentation and its size check per 640x512 frame, LiDAR detection
# per HDL-32E scan, one core), and reading per-point times (clusters, and a raw scan's fields
# carried through detection).
# Close other work first: the figures are wall-clock on this machine.
# Usage: scripts/benchmark.sh [google-benchmark options, passed to each benchmark]
set -euo pipefail
# shellcheck source=scripts/workspace.sh
source "$(dirname "${BASH_SOURCE[0]}")/workspace.sh"
prepare_workspace --bench
echo "machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), $(nproc) cores" >&2
# Five repetitions, reported as mean / median / spread: single runs on a shared machine vary.
for benchmark in loss_benchmark dataset_append_benchmark detection_benchmark point_time_benchmark; do
  "$bin/$benchmark" --benchmark_counters_tabular=true \
    --benchmark_repetitions=5 --benchmark_report_aggregates_only=true "$@"
done
