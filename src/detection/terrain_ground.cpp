#include "thermal_lidar_calibration/detection/terrain_ground.hpp"

#include "fast_math.hpp"

#include <pcl/point_types.h>
#include <pcl/sample_consensus/ransac.h>
#include <pcl/sample_consensus/sac_model_perpendicular_plane.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

namespace thermal_lidar_calibration {
namespace detection {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kPi = 3.14159265f;
// Levelling: lowest point per 2 m x 2 m cell, nearer than 1.5 m ignored (the vehicle itself);
// a plane within 0.2 m of the most minima (PCL RANSAC, deterministic seed), then least squares.
constexpr float kLevelCellM = 2.0f;
constexpr float kLevelMinRangeM = 1.5f;
constexpr double kLevelInlierM = 0.2;
constexpr int kLevelMinCells = 8;
// The RANSAC plane fits the largest flat patch; on rolling ground the mean orientation is
// wanted, so the plane is refitted (orthogonal least squares) to the minima within this band.
constexpr float kLevelRefitBandM = 0.5f;

// Plane n.p + d = 0 (|n| = 1) through the minima within `band` of the given plane.
bool refitPlane(const pcl::PointCloud<pcl::PointXYZ>& minima, float band, Eigen::Vector3f* normal, float* d) {
  Eigen::Vector3f sum = Eigen::Vector3f::Zero();
  std::vector<Eigen::Vector3f> near;
  for (const auto& q : minima) {
    const Eigen::Vector3f p(q.x, q.y, q.z);
    if (std::fabs(normal->dot(p) + *d) > band) continue;
    near.push_back(p);
    sum += p;
  }
  if (static_cast<int>(near.size()) < kLevelMinCells) return false;
  const Eigen::Vector3f mean = sum / static_cast<float>(near.size());
  Eigen::Matrix3f cov = Eigen::Matrix3f::Zero();
  for (const auto& p : near) cov += (p - mean) * (p - mean).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3f> eig(cov);
  Eigen::Vector3f n = eig.eigenvectors().col(0);  // smallest eigenvalue
  if (n.z() < 0) n = -n;
  *normal = n;
  *d = -n.dot(mean);
  return true;
}

}  // namespace

TerrainGround::TerrainGround(const LidarGroundConfig& config) : config_(config) { config_.validate(); }

void TerrainGround::fitLevellingPlane(const std::vector<Eigen::Vector3f>& points) {
  const float radius = static_cast<float>(config_.level_radius_m);
  const int side = static_cast<int>(std::ceil(2.f * radius / kLevelCellM));
  std::vector<Eigen::Vector3f> lowest(static_cast<std::size_t>(side) * side, Eigen::Vector3f(0, 0, kInf));
  for (const Eigen::Vector3f& p : points) {
    if (!isFinite(p.x(), p.y(), p.z())) continue;
    const float r2 = p.x() * p.x() + p.y() * p.y();
    if (r2 < kLevelMinRangeM * kLevelMinRangeM || r2 >= radius * radius) continue;
    const int cx = std::min(side - 1, static_cast<int>((p.x() + radius) / kLevelCellM));
    const int cy = std::min(side - 1, static_cast<int>((p.y() + radius) / kLevelCellM));
    Eigen::Vector3f& low = lowest[static_cast<std::size_t>(cy) * side + cx];
    if (p.z() < low.z()) low = p;
  }
  pcl::PointCloud<pcl::PointXYZ>::Ptr minima(new pcl::PointCloud<pcl::PointXYZ>);
  for (const Eigen::Vector3f& p : lowest) {
    if (p.z() < kInf) minima->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
  }
  R_level_sensor_.setIdentity();
  levelled_ok_ = false;
  tilt_deg_ = 0;
  double plane_z = 0;  // height of the plane under the sensor, in the levelled frame
  if (static_cast<int>(minima->size()) >= kLevelMinCells) {
    // RANSAC over planes within max_tilt_deg of level, then the plane refitted to its inliers:
    // pcl::SACSegmentation's steps, taken from libpcl_sample_consensus directly so that no
    // program linking the detectors loads libpcl_segmentation (CMakeLists.txt says why).
    auto model = std::make_shared<pcl::SampleConsensusModelPerpendicularPlane<pcl::PointXYZ>>(minima);
    model->setAxis(Eigen::Vector3f::UnitZ());
    model->setEpsAngle(config_.max_tilt_deg * M_PI / 180.0);
    pcl::RandomSampleConsensus<pcl::PointXYZ> ransac(model, kLevelInlierM);
    ransac.setMaxIterations(200);
    Eigen::VectorXf coefficients;
    pcl::Indices inliers;
    if (ransac.computeModel(0)) {
      ransac.getInliers(inliers);
      ransac.getModelCoefficients(coefficients);
      Eigen::VectorXf refined;
      model->optimizeModelCoefficients(inliers, coefficients, refined);
      coefficients = refined;
      model->selectWithinDistance(coefficients, kLevelInlierM, inliers);
    }
    if (coefficients.size() == 4 && static_cast<int>(inliers.size()) >= kLevelMinCells) {
      Eigen::Vector3f normal = coefficients.head<3>();
      float d = coefficients[3];
      const float norm = normal.norm();
      normal /= norm;
      d /= norm;
      if (normal.z() < 0) {
        normal = -normal;
        d = -d;
      }
      for (int pass = 0; pass < 2; ++pass) refitPlane(*minima, kLevelRefitBandM, &normal, &d);
      const double tilt = std::acos(std::min(1.f, normal.z())) * 180.0 / M_PI;
      if (tilt <= config_.max_tilt_deg) {
        R_level_sensor_ = Eigen::Quaternionf::FromTwoVectors(normal, Eigen::Vector3f::UnitZ()).toRotationMatrix();
        tilt_deg_ = tilt;
        plane_z = -d;  // n.p + d = 0 -> in the levelled frame z = -d
        levelled_ok_ = true;
      }
    }
  }
  if (!levelled_ok_ && !minima->empty()) {
    // No plane: measure from the median of the minima, unrotated.
    std::vector<float> z;
    for (const auto& p : *minima) z.push_back(p.z);
    std::nth_element(z.begin(), z.begin() + z.size() / 2, z.end());
    plane_z = z[z.size() / 2];
  }
  sensor_height_m_ = -plane_z;
}

int TerrainGround::cellOf(const Eigen::Vector2f& xy, float* range) const {
  const float r = xy.norm();
  *range = r;
  if (!(r < max_range_m_)) return -1;
  const int sectors = config_.sectors;
  int s = static_cast<int>((fastAtan2(xy.y(), xy.x()) + kPi) * (sectors / (2.f * kPi)));
  s = std::min(std::max(s, 0), sectors - 1);
  const int b = std::min(bins_ - 1, static_cast<int>(r / static_cast<float>(config_.bin_m)));
  return s * bins_ + b;
}

void TerrainGround::estimate(const std::vector<Eigen::Vector3f>& points, double max_range_m) {
  max_range_m_ = max_range_m;
  bins_ = std::max(1, static_cast<int>(std::ceil(max_range_m / config_.bin_m)));
  const std::size_t cells = static_cast<std::size_t>(config_.sectors) * bins_;
  fitLevellingPlane(points);
  const float shift = static_cast<float>(-sensor_height_m_);  // plane height in the levelled frame

  const std::size_t n = points.size();
  levelled_.resize(n);
  height_.assign(n, kNaN);
  cell_of_point_.assign(n, -1);
  cell_min_.assign(cells, kInf);
  cell_max_.assign(cells, -kInf);
  cell_min_r_.assign(cells, 0.f);
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3f& p = points[i];
    if (!isFinite(p.x(), p.y(), p.z())) {
      levelled_[i].setConstant(kNaN);
      continue;
    }
    Eigen::Vector3f q = R_level_sensor_ * p;
    q.z() -= shift;
    levelled_[i] = q;
    float r = 0;
    const int k = cellOf(q.head<2>(), &r);
    cell_of_point_[i] = k;
    if (k < 0) continue;
    if (q.z() < cell_min_[k]) {
      cell_min_[k] = q.z();
      cell_min_r_[k] = r;
    }
    cell_max_[k] = std::max(cell_max_[k], q.z());
  }
  followSectors();
  for (std::size_t i = 0; i < n; ++i) {
    const int k = cell_of_point_[i];
    if (k < 0) continue;
    const Eigen::Vector3f& q = levelled_[i];
    const float r = q.head<2>().norm();
    height_[i] = q.z() - (ground_z_[k] + ground_slope_[k] * (r - ground_r_[k]));
  }
}

void TerrainGround::followSectors() {
  const std::size_t cells = cell_min_.size();
  ground_z_.assign(cells, 0.f);
  ground_r_.assign(cells, 0.f);
  ground_slope_.assign(cells, 0.f);
  const float max_slope = static_cast<float>(std::tan(config_.max_slope_deg * M_PI / 180.0));
  const float max_step = static_cast<float>(config_.max_step_m);
  const float tolerance = static_cast<float>(config_.tolerance_m);
  const float spread = static_cast<float>(config_.object_spread_m);
  const float bin = static_cast<float>(config_.bin_m);
  std::vector<float> anchor_r, anchor_z;
  for (int s = 0; s < config_.sectors; ++s) {
    // The plane under the sensor is the first anchor.
    anchor_r.assign(1, 0.f);
    anchor_z.assign(1, 0.f);
    float slope = 0.f;
    for (int b = 0; b < bins_; ++b) {
      const std::size_t k = static_cast<std::size_t>(s) * bins_ + b;
      if (!(cell_min_[k] < kInf)) continue;
      const float m = cell_min_[k];
      const float dr = std::max(0.f, cell_min_r_[k] - anchor_r.back());
      const float predicted = anchor_z.back() + slope * dr;
      const bool object_cell = cell_max_[k] - m > spread;
      const float allowed = object_cell ? tolerance : max_step + max_slope * dr;
      if (std::fabs(m - predicted) > allowed) continue;
      if (dr <= 0.f) continue;  // same range as the last anchor
      anchor_r.push_back(cell_min_r_[k]);
      anchor_z.push_back(m);
      const std::size_t a = anchor_r.size();
      slope = (anchor_z[a - 1] - anchor_z[a - 2]) / (anchor_r[a - 1] - anchor_r[a - 2]);
      slope = std::min(max_slope, std::max(-max_slope, slope));
    }
    // Ground line per bin: through the anchors that bracket the bin centre; flat past the last.
    std::size_t a = 0;
    for (int b = 0; b < bins_; ++b) {
      const std::size_t k = static_cast<std::size_t>(s) * bins_ + b;
      const float centre = (static_cast<float>(b) + 0.5f) * bin;
      while (a + 1 < anchor_r.size() && anchor_r[a + 1] <= centre) ++a;
      ground_r_[k] = anchor_r[a];
      ground_z_[k] = anchor_z[a];
      ground_slope_[k] = a + 1 < anchor_r.size()
                             ? (anchor_z[a + 1] - anchor_z[a]) / (anchor_r[a + 1] - anchor_r[a])
                             : 0.f;
    }
  }
}

float TerrainGround::groundAt(const Eigen::Vector2f& xy) const {
  float r = 0;
  const int k = cellOf(xy, &r);
  if (k < 0 || ground_z_.empty()) return 0.f;
  return ground_z_[k] + ground_slope_[k] * (r - ground_r_[k]);
}

}  // namespace detection
}  // namespace thermal_lidar_calibration
