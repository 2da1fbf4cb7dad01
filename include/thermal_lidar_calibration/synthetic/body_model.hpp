#pragma once
// Solid primitives (capsules, ellipsoids), ray intersection, and the body-shaped person model
// used by the synthetic rig. Everything is in metres; frames are whatever the caller uses.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <vector>

namespace thermal_lidar_calibration {
namespace synthetic {

struct Ray {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();  // unit length
};

// All points within `radius` of the segment a-b.
struct Capsule {
  Eigen::Vector3d a = Eigen::Vector3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  double radius = 0.0;
};

// Points x with |diag(1/radii) axes^T (x - centre)| <= 1; `axes` columns are unit axes.
struct Ellipsoid {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
  Eigen::Vector3d radii = Eigen::Vector3d::Ones();
};

// Smallest ray parameter t > 0 at which the ray enters the primitive, if any.
bool intersectCapsule(const Capsule& capsule, const Ray& ray, double* t);
bool intersectEllipsoid(const Ellipsoid& ellipsoid, const Ray& ray, double* t);
// Ray against the horizontal plane z = plane_z.
bool intersectHorizontalPlane(double plane_z, const Ray& ray, double* t);

// A union of primitives with a bounding sphere for culling.
class Solid {
 public:
  void add(const Capsule& capsule);
  void add(const Ellipsoid& ellipsoid);
  // Nearest entry t in (0, t_max); false if the ray misses or the hit is not nearer than t_max.
  bool intersect(const Ray& ray, double t_max, double* t) const;
  // True if the ray passes within the bounding sphere (cheap pre-test).
  bool mayIntersect(const Ray& ray) const;
  Solid transformed(const Eigen::Isometry3d& T_target_source) const;

  const Eigen::Vector3d& boundingCentre() const { return centre_; }
  double boundingRadius() const { return radius_; }
  // Corners of the axis-aligned box around every primitive (for projection bounds).
  std::vector<Eigen::Vector3d> boundingBoxCorners() const;

 private:
  void updateBounds();
  std::vector<Capsule> capsules_;
  std::vector<Ellipsoid> ellipsoids_;
  Eigen::Vector3d centre_ = Eigen::Vector3d::Zero();
  double radius_ = 0.0;
  Eigen::Vector3d box_min_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d box_max_ = Eigen::Vector3d::Zero();
};

// Where and how a person stands. The body is built in a frame with z up and the feet on z = 0.
struct BodyPose {
  Eigen::Vector2d ground_xy = Eigen::Vector2d::Zero();  // m
  double heading_rad = 0.0;     // direction the person faces, about +z
  double height_m = 1.75;       // top of the head above the ground
  double gait_phase_rad = 0.0;  // walking cycle phase
  double swing_rad = 0.0;       // leg/arm swing amplitude; 0 = standing still
};

// Legs, torso, arms, neck and head as capsules and ellipsoids scaled with height.
Solid makePersonBody(const BodyPose& pose);
// Non-person clutter the LiDAR detector may mistake for a person.
Solid makePost(const Eigen::Vector2d& ground_xy, double height_m, double radius_m);
Solid makeBush(const Eigen::Vector2d& ground_xy, const Eigen::Vector3d& radii_m);
// A parked car's body (two rounded slabs, 4.2 x 1.8 x 1.5 m) and its engine block at the front
// (`engine` true: only the engine, for its own temperature), heading `yaw_rad`.
Solid makeParkedVehicle(const Eigen::Vector2d& ground_xy, double yaw_rad, bool engine);
// A four-legged animal the size of a sheep or a large dog (body 0.9 m long, back at ~0.75 m):
// at body temperature, but not person-shaped.
Solid makeAnimal(const Eigen::Vector2d& ground_xy, double yaw_rad);

}  // namespace synthetic
}  // namespace thermal_lidar_calibration
