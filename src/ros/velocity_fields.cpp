#include "thermal_lidar_calibration/ros/velocity_fields.hpp"

#include "cloud_fields.hpp"
#include "thermal_lidar_calibration/core/person_timing.hpp"

#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>

namespace thermal_lidar_calibration {
namespace ros_io {

sensor_msgs::PointCloud2 withVelocityFields(const sensor_msgs::PointCloud2& clusters,
                                            const std::vector<PersonMotion>& motion, const std::string& topic) {
  const cloud_fields::CloudLayout layout = cloud_fields::checkCloudLayout(clusters, topic, /*need_label=*/true);
  // Per measured person: vx, vy, vz, vx_se, vy_se, as the fields are laid out.
  std::map<std::int32_t, std::array<float, 5>> by_label;
  for (const PersonMotion& m : motion) {
    if (!m.measured()) continue;
    const Eigen::Vector3f v = deskewVelocity(m).cast<float>();
    const Eigen::Vector3f se = deskewVelocityStdError(m).cast<float>();
    by_label[m.label] = {v.x(), v.y(), v.z(), se.x(), se.y()};
  }
  // The same points, dense, with the old fields (less any old velocity) followed by vx, vy, vz.
  sensor_msgs::PointCloud2 out;
  out.header = clusters.header;
  out.height = 1;
  out.width = static_cast<std::uint32_t>(layout.points);
  out.is_bigendian = clusters.is_bigendian;
  out.is_dense = clusters.is_dense;
  std::vector<const sensor_msgs::PointField*> kept;
  std::uint32_t step = 0;
  for (const sensor_msgs::PointField& f : clusters.fields) {
    if (f.name == kVelocityFields[0] || f.name == kVelocityFields[1] || f.name == kVelocityFields[2] ||
        f.name == kVelocityErrorFields[0] || f.name == kVelocityErrorFields[1]) {
      continue;
    }
    cloud_fields::checkFieldFits(clusters, f, topic);
    const std::size_t bytes = cloud_fields::datatypeSize(f.datatype) * std::max<std::uint32_t>(1, f.count);
    if (f.offset + bytes > clusters.point_step) {
      cloud_fields::fail(topic, "PointCloud2 field '" + f.name + "' (" + std::to_string(f.count) +
                                    " values) lies outside point_step; fix the publisher's field layout");
    }
    sensor_msgs::PointField g = f;
    g.offset = step;
    step += static_cast<std::uint32_t>(bytes);
    out.fields.push_back(g);
    kept.push_back(&f);
  }
  const std::uint32_t velocity_offset = step;
  for (int k = 0; k < 5; ++k) {
    sensor_msgs::PointField v;
    v.name = k < 3 ? kVelocityFields[k] : kVelocityErrorFields[k - 3];
    v.offset = step;
    v.datatype = sensor_msgs::PointField::FLOAT32;
    v.count = 1;
    step += 4;
    out.fields.push_back(v);
  }
  out.point_step = step;
  out.row_step = step * out.width;
  out.data.resize(static_cast<std::size_t>(out.row_step));
  for (std::size_t i = 0; i < layout.points; ++i) {
    const std::uint8_t* from = cloud_fields::pointAt(clusters, i);
    std::uint8_t* to = out.data.data() + i * step;
    for (std::size_t f = 0; f < kept.size(); ++f) {
      const std::size_t bytes = cloud_fields::datatypeSize(kept[f]->datatype) * std::max<std::uint32_t>(1, kept[f]->count);
      std::memcpy(to + out.fields[f].offset, from + kept[f]->offset, bytes);
    }
    const double label = cloud_fields::readScalar(from + layout.label->offset, layout.label->datatype);
    constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
    std::array<float, 5> values = {0.0f, 0.0f, 0.0f, kNaN, kNaN};  // not measured
    if (std::isfinite(label)) {
      const auto it = by_label.find(static_cast<std::int32_t>(label));
      if (it != by_label.end()) values = it->second;
    }
    std::memcpy(to + velocity_offset, values.data(), sizeof(values));
  }
  return out;
}

std::vector<PersonMotion> motionFromFields(const std::vector<std::int32_t>& labels,
                                           const std::vector<Eigen::Vector3f>& velocity,
                                           const std::vector<Eigen::Vector2f>& velocity_se) {
  std::map<std::int32_t, PersonMotion> by_label;
  if (velocity.size() != labels.size() || velocity_se.size() != labels.size()) return {};
  for (std::size_t i = 0; i < labels.size(); ++i) {
    if (std::isnan(velocity_se[i].x()) || std::isnan(velocity_se[i].y()) || by_label.count(labels[i]) != 0) continue;
    PersonMotion m;
    m.label = labels[i];
    m.velocity_mps = velocity[i].cast<double>();
    m.std_error_mps = Eigen::Vector3d(velocity_se[i].x(), velocity_se[i].y(), 0.0);
    m.scans = 2;
    by_label[m.label] = m;
  }
  std::vector<PersonMotion> out;
  for (const auto& [label, m] : by_label) out.push_back(m);
  return out;
}

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
