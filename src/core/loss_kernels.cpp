// The hot loops. Each public kernel is compiled for AVX-512, AVX2+FMA and baseline x86-64
// (GCC target_clones picks one at load time), and vectorises across points, never across
// candidates: a candidate's sum is computed the same way whatever the batch or thread it is in,
// which is what keeps results identical for any thread count.

#include "loss_kernels.hpp"

#include <cmath>

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define TLC_MULTIVERSION __attribute__((target_clones("avx512f", "arch=x86-64-v3", "default")))
#else
#define TLC_MULTIVERSION
#endif
#define TLC_INLINE inline __attribute__((always_inline))

namespace thermal_lidar_calibration {
namespace kernels {
namespace {

// Far-away projections (z -> 0+) are clamped so float->int conversions stay defined; a point
// 1e6 px away already costs far more than the behind-camera penalty.
constexpr float kLimit = 1e6f;
constexpr float kNormalisedLimit = 1e4f;

TLC_INLINE float clampf(float x, float lo, float hi) { return fminf(fmaxf(x, lo), hi); }

// Projects one point; returns false when it is behind the camera (z <= 0).
template <bool kDistorted>
TLC_INLINE bool project(const float* m, const Lens& lens, float px, float py, float pz, float& u,
                        float& v) {
  const float X = m[0] * px + m[1] * py + m[2] * pz + m[3];
  const float Y = m[4] * px + m[5] * py + m[6] * pz + m[7];
  const float Z = m[8] * px + m[9] * py + m[10] * pz + m[11];
  const bool front = Z > 0.0f;
  const float inv = 1.0f / (front ? Z : 1.0f);
  if constexpr (kDistorted) {
    const float x = clampf(X * inv, -kNormalisedLimit, kNormalisedLimit);
    const float y = clampf(Y * inv, -kNormalisedLimit, kNormalisedLimit);
    const float r2 = x * x + y * y;
    const float radial = 1.0f + r2 * (lens.k1 + r2 * (lens.k2 + r2 * lens.k3));
    const float xd = x * radial + 2.0f * lens.p1 * x * y + lens.p2 * (r2 + 2.0f * x * x);
    const float yd = y * radial + lens.p1 * (r2 + 2.0f * y * y) + 2.0f * lens.p2 * x * y;
    u = lens.fx * xd + lens.skew * yd + lens.cx;
    v = lens.fy * yd + lens.cy;
  } else {
    u = X * inv;
    v = Y * inv;
  }
  u = clampf(u, -kLimit, kLimit);
  v = clampf(v, -kLimit, kLimit);
  return front;
}

// Nearest pixel centre, ties up: floor(x + 0.5) by truncation, valid since |x| <= kLimit.
TLC_INLINE float roundHalfUp(float x) {
  const float s = x + 0.5f;
  const float t = static_cast<float>(static_cast<int>(s));
  return t > s ? t - 1.0f : t;
}

template <bool kDistorted>
TLC_INLINE float sumNearest(const float* m, const Lens& lens, const Points& p, const MapView& map,
                            float penalty) {
  float acc = 0.0f;
#pragma omp simd reduction(+ : acc)
  for (int i = 0; i < p.count; ++i) {
    float u, v;
    const bool front = project<kDistorted>(m, lens, p.x[i], p.y[i], p.z[i], u, v);
    const float ru = roundHalfUp(u);
    const float rv = roundHalfUp(v);
    const float cu = clampf(ru, map.x0, map.x1);
    const float cv = clampf(rv, map.y0, map.y1);
    const int index = static_cast<int>(cv - map.y0) * map.width + static_cast<int>(cu - map.x0);
    const float d = fabsf(ru - cu) + fabsf(rv - cv) + map.values[index];
    acc += front ? d : penalty;
  }
  return acc;
}

template <bool kDistorted>
TLC_INLINE float sumBilinear(const float* m, const Lens& lens, const Points& p,
                             const MapView& map, float penalty) {
  const float max_ix = map.x1 - map.x0 - 1.0f;  // the crop is at least 2x2
  const float max_iy = map.y1 - map.y0 - 1.0f;
  float acc = 0.0f;
#pragma omp simd reduction(+ : acc)
  for (int i = 0; i < p.count; ++i) {
    float u, v;
    const bool front = project<kDistorted>(m, lens, p.x[i], p.y[i], p.z[i], u, v);
    const float cu = clampf(u, map.x0, map.x1);
    const float cv = clampf(v, map.y0, map.y1);
    const float fx = cu - map.x0;
    const float fy = cv - map.y0;
    const float ix = fminf(static_cast<float>(static_cast<int>(fx)), max_ix);
    const float iy = fminf(static_cast<float>(static_cast<int>(fy)), max_iy);
    const float ax = fx - ix;
    const float ay = fy - iy;
    const int index = static_cast<int>(iy) * map.width + static_cast<int>(ix);
    const float v00 = map.values[index];
    const float v01 = map.values[index + 1];
    const float v10 = map.values[index + map.width];
    const float v11 = map.values[index + map.width + 1];
    const float top = v00 + ax * (v01 - v00);
    const float bottom = v10 + ax * (v11 - v10);
    const float d = fabsf(u - cu) + fabsf(v - cv) + top + ay * (bottom - top);
    acc += front ? d : penalty;
  }
  return acc;
}

template <bool kDistorted>
TLC_INLINE int countInsideImpl(const float* m, const Lens& lens, const Points& p, int width,
                               int height) {
  const float max_u = static_cast<float>(width - 1);
  const float max_v = static_cast<float>(height - 1);
  int inside = 0;
#pragma omp simd reduction(+ : inside)
  for (int i = 0; i < p.count; ++i) {
    float u, v;
    const bool front = project<kDistorted>(m, lens, p.x[i], p.y[i], p.z[i], u, v);
    const float ru = roundHalfUp(u);
    const float rv = roundHalfUp(v);
    inside += (front && ru >= 0.0f && ru <= max_u && rv >= 0.0f && rv <= max_v) ? 1 : 0;
  }
  return inside;
}

const Lens kNoLens{1, 1, 0, 0, 0, 0, 0, 0, 0, 0};

}  // namespace

TLC_MULTIVERSION float sumPsiNearestPinhole(const float* m, const Points& p, const MapView& map,
                                            float penalty) {
  return sumNearest<false>(m, kNoLens, p, map, penalty);
}

TLC_MULTIVERSION float sumPsiNearestDistorted(const float* m, const Lens& lens, const Points& p,
                                              const MapView& map, float penalty) {
  return sumNearest<true>(m, lens, p, map, penalty);
}

TLC_MULTIVERSION float sumPsiBilinearPinhole(const float* m, const Points& p, const MapView& map,
                                             float penalty) {
  return sumBilinear<false>(m, kNoLens, p, map, penalty);
}

TLC_MULTIVERSION float sumPsiBilinearDistorted(const float* m, const Lens& lens, const Points& p,
                                               const MapView& map, float penalty) {
  return sumBilinear<true>(m, lens, p, map, penalty);
}

TLC_MULTIVERSION int countInside(const float* m, bool distorted, const Lens& lens,
                                 const Points& p, int width, int height) {
  return distorted ? countInsideImpl<true>(m, lens, p, width, height)
                   : countInsideImpl<false>(m, kNoLens, p, width, height);
}

}  // namespace kernels
}  // namespace thermal_lidar_calibration
