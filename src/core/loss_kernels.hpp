#pragma once
// Internal: the inner loops of Eq. (1)-(2). One candidate, one pair's points, summed psi.
// Kept apart from loss.cpp so the hot code is small and compiled once per CPU level.

#include <cstdint>

namespace thermal_lidar_calibration {
namespace kernels {

// The distance map of one pair, cropped to its people's box (see distance_map.hpp).
struct MapView {
  const float* values;
  int width;
  float x0, y0, x1, y1;  // crop box, inclusive pixel-centre bounds
};

// Lens terms used only by the distorted kernels.
struct Lens {
  float fx, fy, cx, cy, skew, k1, k2, p1, p2, k3;
  bool radial_only = false;  // p1 = p2 = skew = 0: skip the tangential arithmetic
};

// m: row-major 3x4. Pinhole kernels expect K [R | t] (one mat-vec and one reciprocal per point);
// distorted kernels expect [R | t] and apply the lens after the division.
// Points are processed in blocks of kPointBlock; the arrays must be readable (any finite
// values) up to `count` rounded up to a multiple of kPointBlock, as PreparedPair pads them.
constexpr int kPointBlock = 8;
struct Points {
  const float* x;
  const float* y;
  const float* z;
  int count;
};

// Sum of psi over the points, with the nearest or the bilinear pixel rule; `lens` is read only
// when `distorted`. margin > 0 (beyond the paper): a point in front of the camera scores
// max(0, psi - margin) instead; margin = 0 runs the paper's code unchanged.
float sumPsi(const float* m, bool distorted, bool bilinear, const Lens& lens, const Points& p,
             const MapView& map, float penalty, float margin = 0.0f);

// Points in front of the camera whose nearest pixel lies inside a width x height image.
int countInside(const float* m, bool distorted, const Lens& lens, const Points& p, int width,
                int height);

// The portable versions the functions above fall back to on CPUs without AVX2+FMA, exposed so
// tests can check them against the vector code on any machine.
float sumPsiScalar(const float* m, bool distorted, bool bilinear, const Lens& lens,
                   const Points& p, const MapView& map, float penalty, float margin = 0.0f);
int countInsideScalar(const float* m, bool distorted, const Lens& lens, const Points& p,
                      int width, int height);

// A pair's ring ends as sumRingEnds reads them (ring_ends.hpp), one array per field, each
// readable up to `count` rounded up to a multiple of kPointBlock (the padding lanes are masked
// out): the end's point (a copy of the pair's, so the vector code loads rather than gathers it),
// its side (+1 / -1), the image row of its outline's first column, how many rows the outline has,
// where its columns start in `edges` (all the pair's outline columns, NaN where a row has none),
// where the end lies inside on average, and whether the end before it is its ring's other end.
struct RingEnds {
  const float* x;
  const float* y;
  const float* z;
  const float* side;
  const float* first_row;
  const std::int32_t* rows;
  const std::int32_t* offset;
  const float* half_step;
  const float* edges;
  const std::uint8_t* pairs_previous;  // 1: the end before it is the other end of its ring
  int count;
};

// The ends' cost at their points' pixels: ringPairCost of each ring whose two ends are both
// measured, ringEndCost of every other end (an end behind the camera scores `cap`).
float sumRingEnds(const float* m, bool distorted, const Lens& lens, const RingEnds& ends, float cap,
                  float width_weight);
// The portable version sumRingEnds falls back to without AVX2+FMA (for tests, as sumPsiScalar).
float sumRingEndsScalar(const float* m, bool distorted, const Lens& lens, const RingEnds& ends, float cap,
                        float width_weight);

// One point's pixel as the kernels project it; false when it is behind the camera.
bool projectPoint(const float* m, bool distorted, const Lens& lens, float x, float y, float z, float& u,
                  float& v);

// True when sumPsi / countInside run the AVX2+FMA code on this CPU; false when they are the
// portable code (then comparing the two compares the portable code with itself).
bool vectorPathActive();

// countInside(...) >= needed, deciding as soon as the remaining points cannot change it.
bool atLeastInside(const float* m, bool distorted, const Lens& lens, const Points& p, int width,
                   int height, int needed);

}  // namespace kernels
}  // namespace thermal_lidar_calibration
