#!/usr/bin/env bash
# Re-measures the speed figures of the README: loss throughput per core and the whole default
# run (Algorithm 2 at Table 1 + refinement) on 60 pairs of ~100 points with 2 threads.
# Close other work first: the figures are wall-clock on this machine.
set -euo pipefail
export PATH=/usr/bin:/bin:/usr/sbin:/sbin:$PATH
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$repo/scripts/install_deps.sh"
ws="$(bash "$repo/scripts/build.sh" | tail -n 1)"
echo "machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), $(nproc) cores" >&2
"$ws/devel/lib/thermal_lidar_calibration/loss_benchmark" --benchmark_counters_tabular=true "$@"
