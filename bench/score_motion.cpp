// How well the neighbouring scans measure each person's motion relative to the LiDAR (issue 21's
// estimateMotion), against the synthetic rig's own (SyntheticRig::personMotion at the person's
// mean point time). Takes make_synthetic_bag's options (no bag is written): renders the drive,
// summarises every scan as the ingest does, estimates every measured person's velocity and
// prints the error's mean and spread along the LiDAR's x (the travel) and y, over the drive, by
// side of the path and by range. A bias that differs between the sides would move the people on
// the image's left and right apart, as a roll does; the spread times the offset is how far a
// pair's points land off.
// Usage: score_motion [make_synthetic_bag options, e.g. --rig fieldsafe --speed-profile field
//        --walking-fraction 0.5 --noise realistic --lidar-stamp end --lidar-point-time --seed 2]

#include "thermal_lidar_calibration/core/person_motion.hpp"
#include "thermal_lidar_calibration/synthetic/synthetic_rig.hpp"
#include "thermal_lidar_calibration/tools/make_synthetic_bag_options.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

namespace tlc = thermal_lidar_calibration;

namespace {

struct ErrorSum {
  int n = 0;
  double sx = 0.0, sy = 0.0, sxx = 0.0, syy = 0.0;
  void add(double ex, double ey) {
    ++n;
    sx += ex;
    sy += ey;
    sxx += ex * ex;
    syy += ey * ey;
  }
  void print(const char* name) const {
    if (n == 0) return;
    const double mx = sx / n, my = sy / n;
    std::printf("%-22s %6d  %+8.4f %7.4f  %+8.4f %7.4f\n", name, n, mx, std::sqrt(std::max(0.0, sxx / n - mx * mx)),
                my, std::sqrt(std::max(0.0, syy / n - my * my)));
  }
};

}  // namespace

int main(int argc, char** argv) {
  try {
    std::vector<std::string> args(argv + 1, argv + argc);
    args.push_back("--output");  // required by the options, never written
    args.push_back("/dev/null");
    const tlc::synthetic::SyntheticConfig config =
        tlc::ros_io::syntheticConfigFrom(tlc::ros_io::parseMakeSyntheticBagOptions(args));
    const tlc::synthetic::SyntheticRig rig(config);
    std::vector<tlc::ScanPeople> scans;
    scans.reserve(static_cast<std::size_t>(config.frames));
    for (int i = 0; i < config.frames; ++i) {
      const tlc::synthetic::SyntheticFrame f = rig.render(i);
      scans.push_back(tlc::summariseScan(f.stamp_s, f.cluster_points, f.cluster_labels, f.cluster_time_s));
    }
    ErrorSum all, left, right, near, mid, far;
    int unmeasured = 0;
    const tlc::MotionConfig motion;
    for (std::size_t i = 0; i < scans.size(); ++i) {
      const std::vector<tlc::PersonMotion> m = tlc::estimateMotion(scans, i, motion);
      for (std::size_t k = 0; k < m.size(); ++k) {
        const tlc::ScanPeople::Person& p = scans[i].people[k];
        if (p.label < 1 || p.label > static_cast<int>(rig.scene().people().size())) continue;  // a false cluster
        if (!m[k].measured()) {
          ++unmeasured;
          continue;
        }
        const Eigen::Vector3d truth = rig.personMotion(p.label, p.time_s).velocity_mps;
        const double ex = m[k].velocity_mps.x() - truth.x(), ey = m[k].velocity_mps.y() - truth.y();
        all.add(ex, ey);
        (p.centroid.y() >= 0.0 ? left : right).add(ex, ey);
        const double range = p.centroid.head<2>().norm();
        (range < 10.0 ? near : range < 20.0 ? mid : far).add(ex, ey);
      }
    }
    std::printf("velocity error (estimate - truth), m/s   n      x mean   x sd      y mean   y sd\n");
    all.print("every measured person");
    left.print("left of the path");
    right.print("right of the path");
    near.print("range < 10 m");
    mid.print("range 10-20 m");
    far.print("range >= 20 m");
    std::printf("%-22s %6d\n", "not measured", unmeasured);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "score_motion: %s\n", e.what());
    return 2;
  }
}
