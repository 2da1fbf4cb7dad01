#include "thermal_lidar_calibration/synthetic/body_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace thermal_lidar_calibration {
namespace synthetic {
namespace {

constexpr double kEpsilon = 1e-12;

// Entry of the ray into the sphere (centre, radius); false if it misses or starts inside.
bool intersectSphere(const Eigen::Vector3d& centre, double radius, const Ray& ray, double* t) {
  const Eigen::Vector3d oc = ray.origin - centre;
  const double b = ray.direction.dot(oc);
  const double c = oc.squaredNorm() - radius * radius;
  const double h = b * b - c;
  if (h < 0.0) return false;
  const double t0 = -b - std::sqrt(h);
  if (t0 <= 0.0) return false;
  *t = t0;
  return true;
}

}  // namespace

bool intersectCapsule(const Capsule& capsule, const Ray& ray, double* t) {
  // Cylinder body, then the two hemispherical caps (after Inigo Quilez's capsule intersector).
  const Eigen::Vector3d ba = capsule.b - capsule.a;
  const Eigen::Vector3d oa = ray.origin - capsule.a;
  const double baba = ba.dot(ba);
  const double bard = ba.dot(ray.direction);
  const double baoa = ba.dot(oa);
  const double rdoa = ray.direction.dot(oa);
  const double oaoa = oa.dot(oa);
  const double r2 = capsule.radius * capsule.radius;
  const double qa = baba - bard * bard;
  if (qa > kEpsilon * std::max(1.0, baba)) {
    const double qb = baba * rdoa - baoa * bard;
    const double qc = baba * oaoa - baoa * baoa - r2 * baba;
    const double h = qb * qb - qa * qc;
    if (h < 0.0) return false;  // misses the infinite cylinder, so the caps too
    const double tc = (-qb - std::sqrt(h)) / qa;
    const double y = baoa + tc * bard;
    if (y > 0.0 && y < baba) {
      if (tc <= 0.0) return false;
      *t = tc;
      return true;
    }
  }
  double ta = 0.0, tb = 0.0;
  const bool hit_a = intersectSphere(capsule.a, capsule.radius, ray, &ta);
  const bool hit_b = intersectSphere(capsule.b, capsule.radius, ray, &tb);
  if (!hit_a && !hit_b) return false;
  *t = hit_a && hit_b ? std::min(ta, tb) : (hit_a ? ta : tb);
  return true;
}

bool intersectEllipsoid(const Ellipsoid& e, const Ray& ray, double* t) {
  const Eigen::Vector3d inv_r = e.radii.cwiseInverse();
  const Eigen::Vector3d o = (e.axes.transpose() * (ray.origin - e.centre)).cwiseProduct(inv_r);
  const Eigen::Vector3d d = (e.axes.transpose() * ray.direction).cwiseProduct(inv_r);
  const double a = d.dot(d);
  const double b = o.dot(d);
  const double c = o.dot(o) - 1.0;
  const double h = b * b - a * c;
  if (h < 0.0 || a < kEpsilon) return false;
  const double t0 = (-b - std::sqrt(h)) / a;
  if (t0 <= 0.0) return false;
  *t = t0;
  return true;
}

bool intersectHorizontalPlane(double plane_z, const Ray& ray, double* t) {
  if (std::abs(ray.direction.z()) < kEpsilon) return false;
  const double tp = (plane_z - ray.origin.z()) / ray.direction.z();
  if (tp <= 0.0) return false;
  *t = tp;
  return true;
}

void Solid::add(const Capsule& capsule) {
  capsules_.push_back(capsule);
  updateBounds();
}

void Solid::add(const Ellipsoid& ellipsoid) {
  ellipsoids_.push_back(ellipsoid);
  updateBounds();
}

void Solid::updateBounds() {
  const double inf = std::numeric_limits<double>::infinity();
  box_min_ = Eigen::Vector3d::Constant(inf);
  box_max_ = Eigen::Vector3d::Constant(-inf);
  for (const auto& c : capsules_) {
    const Eigen::Vector3d r = Eigen::Vector3d::Constant(c.radius);
    box_min_ = box_min_.cwiseMin(c.a - r).cwiseMin(c.b - r);
    box_max_ = box_max_.cwiseMax(c.a + r).cwiseMax(c.b + r);
  }
  for (const auto& e : ellipsoids_) {
    // Half-extent along each world axis of a rotated ellipsoid.
    Eigen::Vector3d half;
    for (int i = 0; i < 3; ++i) {
      half[i] = (e.axes.row(i).transpose().cwiseProduct(e.radii)).norm();
    }
    box_min_ = box_min_.cwiseMin(e.centre - half);
    box_max_ = box_max_.cwiseMax(e.centre + half);
  }
  centre_ = 0.5 * (box_min_ + box_max_);
  radius_ = 0.0;
  for (const auto& c : capsules_) {
    radius_ = std::max(radius_, (c.a - centre_).norm() + c.radius);
    radius_ = std::max(radius_, (c.b - centre_).norm() + c.radius);
  }
  for (const auto& e : ellipsoids_) {
    radius_ = std::max(radius_, (e.centre - centre_).norm() + e.radii.maxCoeff());
  }
  radius_ += 1e-6;
}

bool Solid::mayIntersect(const Ray& ray) const {
  const Eigen::Vector3d oc = centre_ - ray.origin;
  const double along = oc.dot(ray.direction);
  const double dist2 = oc.squaredNorm() - along * along;
  if (dist2 > radius_ * radius_) return false;
  return along > -radius_;
}

bool Solid::intersect(const Ray& ray, double t_max, double* t) const {
  if (!mayIntersect(ray)) return false;
  double best = t_max;
  bool hit = false;
  double ti = 0.0;
  for (const auto& c : capsules_) {
    if (intersectCapsule(c, ray, &ti) && ti < best) {
      best = ti;
      hit = true;
    }
  }
  for (const auto& e : ellipsoids_) {
    if (intersectEllipsoid(e, ray, &ti) && ti < best) {
      best = ti;
      hit = true;
    }
  }
  if (hit) *t = best;
  return hit;
}

Solid Solid::transformed(const Eigen::Isometry3d& T_target_source) const {
  Solid out;
  out.capsules_.reserve(capsules_.size());
  out.ellipsoids_.reserve(ellipsoids_.size());
  for (const auto& c : capsules_) {
    out.capsules_.push_back({T_target_source * c.a, T_target_source * c.b, c.radius});
  }
  for (const auto& e : ellipsoids_) {
    out.ellipsoids_.push_back({T_target_source * e.centre, T_target_source.linear() * e.axes, e.radii});
  }
  out.updateBounds();
  return out;
}

std::vector<Eigen::Vector3d> Solid::boundingBoxCorners() const {
  std::vector<Eigen::Vector3d> corners;
  corners.reserve(8);
  for (int i = 0; i < 8; ++i) {
    corners.emplace_back((i & 1) ? box_max_.x() : box_min_.x(), (i & 2) ? box_max_.y() : box_min_.y(),
                         (i & 4) ? box_max_.z() : box_min_.z());
  }
  return corners;
}

Solid makePersonBody(const BodyPose& pose) {
  const double h = pose.height_m;
  const double s = h / 1.75;  // width scale relative to a 1.75 m adult
  const double swing = pose.swing_rad * std::sin(pose.gait_phase_rad);
  const double c = std::cos(pose.heading_rad), sn = std::sin(pose.heading_rad);
  // Body frame: x forward, y left, z up, feet on z = 0; rotate by heading, then translate.
  auto world = [&](double x, double y, double z) {
    return Eigen::Vector3d(pose.ground_xy.x() + c * x - sn * y, pose.ground_xy.y() + sn * x + c * y, z);
  };
  Eigen::Matrix3d yaw;
  yaw << c, -sn, 0, sn, c, 0, 0, 0, 1;

  Solid body;
  const double hip_z = 0.52 * h;
  const double leg_r = 0.065 * s;
  const double leg_len = hip_z - leg_r;
  for (int side = -1; side <= 1; side += 2) {
    const double a = side * swing;  // legs swing in opposite phase
    const double hip_y = side * 0.095 * s;
    body.add(Capsule{world(0, hip_y, hip_z), world(leg_len * std::sin(a), hip_y, hip_z - leg_len * std::cos(a)),
                     leg_r});
  }
  const double shoulder_z = 0.81 * h;
  body.add(Ellipsoid{world(0, 0, 0.5 * (hip_z + shoulder_z) + 0.01 * h), yaw,
                     Eigen::Vector3d(0.12 * s, 0.185 * s, 0.5 * (shoulder_z - hip_z) + 0.05 * h)});
  const double arm_r = 0.045 * s;
  const double arm_len = 0.33 * h;
  for (int side = -1; side <= 1; side += 2) {
    const double a = -side * swing;  // arms opposite to the leg on the same side
    const double y = side * 0.215 * s;
    body.add(Capsule{world(0, y, shoulder_z - arm_r),
                     world(arm_len * std::sin(a), side * 0.235 * s, shoulder_z - arm_r - arm_len * std::cos(a)),
                     arm_r});
  }
  const double head_rz = 0.065 * h;
  body.add(Capsule{world(0, 0, shoulder_z), world(0, 0, h - 1.6 * head_rz), 0.05 * s});  // neck
  body.add(Ellipsoid{world(0.005, 0, h - head_rz), yaw, Eigen::Vector3d(0.1 * s, 0.085 * s, head_rz)});
  return body;
}

Solid makePost(const Eigen::Vector2d& ground_xy, double height_m, double radius_m) {
  Solid post;
  post.add(Capsule{Eigen::Vector3d(ground_xy.x(), ground_xy.y(), 0.0),
                   Eigen::Vector3d(ground_xy.x(), ground_xy.y(), height_m - radius_m), radius_m});
  return post;
}

Solid makeBush(const Eigen::Vector2d& ground_xy, const Eigen::Vector3d& radii_m) {
  Solid bush;
  bush.add(Ellipsoid{Eigen::Vector3d(ground_xy.x(), ground_xy.y(), 0.8 * radii_m.z()),
                     Eigen::Matrix3d::Identity(), radii_m});
  return bush;
}

namespace {
// A point given in an object's own frame (x forward, y left, z up) placed at `xy` turned by yaw.
Eigen::Vector3d placed(const Eigen::Vector2d& xy, double yaw, double x, double y, double z) {
  return Eigen::Vector3d(xy.x() + std::cos(yaw) * x - std::sin(yaw) * y,
                         xy.y() + std::sin(yaw) * x + std::cos(yaw) * y, z);
}
Eigen::Matrix3d yawAxes(double yaw) {
  return Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}
}  // namespace

Solid makeParkedVehicle(const Eigen::Vector2d& ground_xy, double yaw_rad, bool engine) {
  Solid s;
  if (engine) {
    s.add(Ellipsoid{placed(ground_xy, yaw_rad, 1.75, 0.0, 0.75), yawAxes(yaw_rad),
                    Eigen::Vector3d(0.45, 0.75, 0.3)});
    return s;
  }
  for (double y : {-0.45, 0.45}) {  // lower body: two capsules along the length
    s.add(Capsule{placed(ground_xy, yaw_rad, -1.6, y, 0.65), placed(ground_xy, yaw_rad, 1.5, y, 0.65), 0.42});
  }
  s.add(Capsule{placed(ground_xy, yaw_rad, -0.9, 0.0, 1.15), placed(ground_xy, yaw_rad, 0.6, 0.0, 1.15), 0.35});  // cabin
  return s;
}

Solid makeAnimal(const Eigen::Vector2d& ground_xy, double yaw_rad) {
  Solid s;
  s.add(Ellipsoid{placed(ground_xy, yaw_rad, 0.0, 0.0, 0.62), yawAxes(yaw_rad), Eigen::Vector3d(0.45, 0.2, 0.2)});
  s.add(Ellipsoid{placed(ground_xy, yaw_rad, 0.55, 0.0, 0.78), yawAxes(yaw_rad), Eigen::Vector3d(0.14, 0.09, 0.1)});
  for (double x : {-0.32, 0.32}) {
    for (double y : {-0.1, 0.1}) {
      s.add(Capsule{placed(ground_xy, yaw_rad, x, y, 0.0), placed(ground_xy, yaw_rad, x, y, 0.5), 0.045});
    }
  }
  return s;
}

}  // namespace synthetic
}  // namespace thermal_lidar_calibration
