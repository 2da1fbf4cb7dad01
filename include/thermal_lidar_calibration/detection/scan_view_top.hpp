#pragma once
// The top of a spinning LiDAR's view in one scan. Its highest beam sweeps a cone: no return lies
// above z = a + b r in the sensor frame (r horizontal range, b the tangent of that beam's
// elevation, a the offset of its origin, ~0.2 m on an HDL-64E). An object whose highest point is
// on that cone may go on above it: a tree trunk or a post under a low top beam (an HDL-64E looks
// 2 deg up: at 15 m nothing above 2.2 m is seen, from a 1.73 m mount) reads as person-high. The
// cone is read off the scan itself: the highest point per range bin lies on it wherever anything
// rises above the top beam (walls, trees, poles), and a line that bounds every bin from above
// and touches many of them is that cone. Only points above the ground count: sloped ground or a
// tilted mount puts ground points on lines of their own. When nothing rises to the top beam (an
// open field under a high top beam, where no person reaches it either), no top is found and
// nothing is judged by it.

#include <Eigen/Core>

#include <vector>

namespace thermal_lidar_calibration {
namespace detection {

class ScanViewTop {
 public:
  // points: sensor frame (x, y, z in m, z roughly up); heights: each point's height above the
  // local ground (NaN where unknown). Only the points higher than min_height_m count.
  void fit(const std::vector<Eigen::Vector3f>& points, const std::vector<float>& heights, float min_height_m);

  bool found() const { return found_; }
  double offsetM() const { return offset_m_; }             // a
  double elevationDeg() const;                              // atan(b)

  // How far the highest of points[indices] lies below the view top, in degrees of elevation seen
  // from the sensor (<= 0: on it); +infinity when no top was found.
  double gapBelowDeg(const std::vector<Eigen::Vector3f>& points, const std::vector<int>& indices) const;

 private:
  bool found_ = false;
  double offset_m_ = 0;  // a
  double slope_ = 0;     // b
  std::vector<float> bin_top_z_, bin_top_r_;  // scratch: highest point per range bin
};

}  // namespace detection
}  // namespace thermal_lidar_calibration
