#include "thermal_lidar_calibration/app/report/static_transform_command.hpp"

#include <Eigen/Geometry>

#include <iomanip>
#include <sstream>

namespace thermal_lidar_calibration {

std::string staticTransformPublisherCommand(const Extrinsic& extrinsic,
                                            const std::string& lidar_frame,
                                            const std::string& child_frame) {
  const Eigen::Isometry3d T_lidar_camera = extrinsic.T_camera_lidar().inverse();
  const Eigen::Quaterniond q(T_lidar_camera.rotation());
  const Eigen::Vector3d& p = T_lidar_camera.translation();
  std::ostringstream s;
  s << std::fixed << std::setprecision(6) << "rosrun tf2_ros static_transform_publisher " << p.x()
    << ' ' << p.y() << ' ' << p.z() << ' ' << std::setprecision(9) << q.x() << ' ' << q.y() << ' '
    << q.z() << ' ' << q.w() << ' ' << lidar_frame << ' ' << child_frame;
  return s.str();
}

}  // namespace thermal_lidar_calibration
