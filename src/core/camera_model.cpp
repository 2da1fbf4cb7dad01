#include "thermal_lidar_calibration/core/camera_model.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace thermal_lidar_calibration {

void CameraModel::validate() const {
  auto fail = [](const std::string& what) {
    throw std::invalid_argument("camera model: " + what);
  };
  if (width <= 0 || height <= 0) {
    fail("image size " + std::to_string(width) + "x" + std::to_string(height) +
         " is not positive; check image_width/image_height in camera_info");
  }
  if (!(fx > 0) || !(fy > 0) || !std::isfinite(fx) || !std::isfinite(fy)) {
    fail("focal lengths fx=" + std::to_string(fx) + ", fy=" + std::to_string(fy) +
         " must be positive; is K all zeros (an uncalibrated camera_info)?");
  }
  if (!std::isfinite(cx) || !std::isfinite(cy) || !std::isfinite(skew)) {
    fail("principal point or skew is not finite");
  }
  for (double d : distortion) {
    if (!std::isfinite(d)) fail("a distortion coefficient is not finite");
  }
}

bool CameraModel::hasDistortion() const {
  for (double d : distortion) {
    if (d != 0.0) return true;
  }
  return false;
}

Eigen::Matrix3d CameraModel::K() const {
  Eigen::Matrix3d k;
  k << fx, skew, cx, 0, fy, cy, 0, 0, 1;
  return k;
}

Eigen::Vector2d CameraModel::distort(const Eigen::Vector2d& n) const {
  const double k1 = distortion[0], k2 = distortion[1], p1 = distortion[2], p2 = distortion[3],
               k3 = distortion[4];
  const double x = n.x(), y = n.y();
  const double r2 = x * x + y * y;
  const double radial = 1.0 + r2 * (k1 + r2 * (k2 + r2 * k3));
  return {x * radial + 2.0 * p1 * x * y + p2 * (r2 + 2.0 * x * x),
          y * radial + p1 * (r2 + 2.0 * y * y) + 2.0 * p2 * x * y};
}

Eigen::Vector2d CameraModel::project(const Eigen::Vector3d& p) const {
  Eigen::Vector2d n(p.x() / p.z(), p.y() / p.z());
  if (hasDistortion()) n = distort(n);
  return {fx * n.x() + skew * n.y() + cx, fy * n.y() + cy};
}

CameraModel CameraModel::fromK(int w, int h, const std::array<double, 9>& k,
                               const std::vector<double>& d) {
  CameraModel c;
  c.width = w;
  c.height = h;
  c.fx = k[0];
  c.skew = k[1];
  c.cx = k[2];
  c.fy = k[4];
  c.cy = k[5];
  if (!d.empty() && d.size() != 5) {
    throw std::invalid_argument("camera model: plumb_bob needs 5 distortion coefficients, got " +
                                std::to_string(d.size()));
  }
  for (std::size_t i = 0; i < d.size(); ++i) c.distortion[i] = d[i];
  c.validate();
  return c;
}

std::string CameraModel::describe() const {
  std::ostringstream s;
  s << width << "x" << height << " fx=" << fx << " fy=" << fy << " cx=" << cx << " cy=" << cy;
  if (hasDistortion()) {
    s << " plumb_bob D=[" << distortion[0] << ", " << distortion[1] << ", " << distortion[2]
      << ", " << distortion[3] << ", " << distortion[4] << "]";
  } else {
    s << " no distortion";
  }
  return s.str();
}

}  // namespace thermal_lidar_calibration
