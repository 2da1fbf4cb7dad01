#pragma once
// Internal (vertical_centring.cpp): the centre of a region of poses, {q : f(q) <= level}, in a
// plane of two pose coordinates or a space of three, traced by bisection along rays from a point
// inside it. `f` maps a batch of points to their losses (one lossBatch call).

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

namespace thermal_lidar_calibration {
namespace region {

// The region is traced out to at most kFirstStep * 2^kMaxDoublings pixels from its centre; a
// direction still inside there counts as unbounded.
constexpr double kFirstStep = 0.25;
constexpr int kMaxDoublings = 12;
constexpr double kMinSearchStep = 1e-3;  // pixels: the best point to this step

template <int N>
using Point = Eigen::Matrix<double, N, 1>;

// Compass search from q: the +-step probes along each axis in one batch, halving the step when
// none improves; it stops early once the loss is at most `good_enough`.
template <int N, typename F>
Point<N> bestPoint(const F& f, Point<N> q, double& fq, double first_step = 1.0,
                   double good_enough = -1.0) {
  fq = f({q})[0];
  for (double step = first_step; step >= kMinSearchStep && !(fq <= good_enough);) {
    std::vector<Point<N>> probes;
    for (int axis = 0; axis < N; ++axis) {
      probes.push_back(q + step * Point<N>::Unit(axis));
      probes.push_back(q - step * Point<N>::Unit(axis));
    }
    const std::vector<double> values = f(probes);
    int best = -1;
    for (int k = 0; k < 2 * N; ++k) {
      if (values[k] < fq) {
        fq = values[k];
        best = k;
      }
    }
    if (best < 0) {
      step *= 0.5;
    } else {
      q = probes[best];
    }
  }
  return q;
}

// Distance from `centre` to the region's edge along each direction (all directions bracketed,
// then bisected, together); false if some direction is still inside at the largest distance.
// `first` (optional, one per direction) is where each bracket's first probe goes.
template <int N, typename F>
bool traceOutline(const F& f, const Point<N>& centre, const std::vector<Point<N>>& directions,
                  double level, int bisections, std::vector<double>& reach,
                  const std::vector<double>* first = nullptr) {
  const std::size_t n = directions.size();
  std::vector<double> inside(n, 0.0), outside(n, kFirstStep);
  if (first && first->size() == n) {
    for (std::size_t k = 0; k < n; ++k) outside[k] = std::max((*first)[k], kFirstStep);
  }
  std::vector<bool> bracketed(n, false);
  for (int round = 0; round <= kMaxDoublings; ++round) {
    std::vector<Point<N>> probes;
    std::vector<std::size_t> which;
    for (std::size_t k = 0; k < n; ++k) {
      if (bracketed[k]) continue;
      probes.push_back(centre + outside[k] * directions[k]);
      which.push_back(k);
    }
    if (probes.empty()) break;
    const std::vector<double> values = f(probes);
    for (std::size_t j = 0; j < which.size(); ++j) {
      const std::size_t k = which[j];
      if (values[j] > level) {
        bracketed[k] = true;
      } else if (round < kMaxDoublings) {
        inside[k] = outside[k];
        outside[k] *= 2.0;
      }
    }
  }
  for (std::size_t k = 0; k < n; ++k) {
    if (!bracketed[k]) return false;
  }
  for (int b = 0; b < bisections; ++b) {
    std::vector<Point<N>> probes(n);
    for (std::size_t k = 0; k < n; ++k) {
      probes[k] = centre + 0.5 * (inside[k] + outside[k]) * directions[k];
    }
    const std::vector<double> values = f(probes);
    for (std::size_t k = 0; k < n; ++k) {
      (values[k] <= level ? inside[k] : outside[k]) = 0.5 * (inside[k] + outside[k]);
    }
  }
  reach = inside;
  return true;
}

// The directions the region is traced along, and how they tile it: around the circle in angle
// order (N = 2, `rays` of them), or the vertices of an icosphere (N = 3: 12, or 42 when `rays`
// asks for more than 12), whose triangles, each with the centre, tile the region.
template <int N>
struct Directions {
  std::vector<Point<N>> rays;
  std::vector<std::array<int, 3>> faces;  // N = 3 only
};

inline std::vector<std::array<int, 3>> icosahedron(std::vector<Eigen::Vector3d>& v) {
  const double g = 0.5 * (1.0 + std::sqrt(5.0));
  v = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
       {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  for (Eigen::Vector3d& p : v) p.normalize();
  return {{{0, 11, 5}}, {{0, 5, 1}},  {{0, 1, 7}},   {{0, 7, 10}}, {{0, 10, 11}}, {{1, 5, 9}}, {{5, 11, 4}},
          {{11, 10, 2}}, {{10, 7, 6}}, {{7, 1, 8}},  {{3, 9, 4}},  {{3, 4, 2}},   {{3, 2, 6}}, {{3, 6, 8}},
          {{3, 8, 9}},  {{4, 9, 5}},  {{2, 4, 11}}, {{6, 2, 10}}, {{8, 6, 7}},   {{9, 8, 1}}};
}

template <int N>
Directions<N> directionsFor(int rays) {
  Directions<N> d;
  if constexpr (N == 2) {
    for (int k = 0; k < rays; ++k) {
      const double angle = 2.0 * M_PI * k / rays;
      d.rays.emplace_back(std::cos(angle), std::sin(angle));
    }
  } else {
    std::vector<Eigen::Vector3d> v;
    std::vector<std::array<int, 3>> faces = icosahedron(v);
    if (rays > 12) {  // each triangle split in four, the new vertices pushed out to the sphere
      std::map<std::pair<int, int>, int> middle;
      const auto between = [&](int a, int b) {
        const std::pair<int, int> key(std::min(a, b), std::max(a, b));
        const auto it = middle.find(key);
        if (it != middle.end()) return it->second;
        v.push_back((v[a] + v[b]).normalized());
        return middle[key] = static_cast<int>(v.size()) - 1;
      };
      std::vector<std::array<int, 3>> finer;
      for (const auto& f : faces) {
        const int ab = between(f[0], f[1]), bc = between(f[1], f[2]), ca = between(f[2], f[0]);
        finer.push_back({{f[0], ab, ca}});
        finer.push_back({{f[1], bc, ab}});
        finer.push_back({{f[2], ca, bc}});
        finer.push_back({{ab, bc, ca}});
      }
      faces = std::move(finer);
    }
    d.rays.assign(v.begin(), v.end());
    d.faces = std::move(faces);
  }
  return d;
}

// Centroid of the region through the points centre + reach[k] * rays[k]: the polygon's (N = 2)
// or the polyhedron's that the icosphere's triangles make with the centre (N = 3).
template <int N>
Point<N> regionCentroid(const Point<N>& centre, const Directions<N>& d, const std::vector<double>& reach) {
  const std::size_t n = d.rays.size();
  double size = 0.0;
  Point<N> sum = Point<N>::Zero();
  if constexpr (N == 2) {
    for (std::size_t k = 0; k < n; ++k) {
      const Point<N> p = reach[k] * d.rays[k];
      const Point<N> q = reach[(k + 1) % n] * d.rays[(k + 1) % n];
      const double cross = p.x() * q.y() - q.x() * p.y();
      size += cross;
      sum += (p + q) * cross / 3.0;
    }
  } else {
    for (const auto& f : d.faces) {
      const Point<N> a = reach[f[0]] * d.rays[f[0]], b = reach[f[1]] * d.rays[f[1]], c = reach[f[2]] * d.rays[f[2]];
      const double volume = std::abs(a.dot(b.cross(c)));  // six times the tetrahedron's
      size += volume;
      sum += volume * (a + b + c) / 4.0;
    }
  }
  if (!(size > 0.0)) return centre;  // degenerate (a point, a line or a plane): stay
  return centre + sum / size;
}

// The region's centroid, traced from `centre` `iterations` times; false if it is unbounded.
template <int N, typename F>
bool regionCentre(const F& f, Point<N>& centre, double level, const Directions<N>& d, int iterations,
                  int bisections, const std::vector<double>* first = nullptr) {
  std::vector<double> reach;
  for (int i = 0; i < iterations; ++i) {
    if (!traceOutline(f, centre, d.rays, level, bisections, reach, i == 0 ? first : nullptr)) return false;
    // A region that is not convex may have its centroid outside: then keep the last centre.
    const Point<N> next = regionCentroid(centre, d, reach);
    if (f({next})[0] > level) break;
    centre = next;
  }
  return true;
}

}  // namespace region
}  // namespace thermal_lidar_calibration
