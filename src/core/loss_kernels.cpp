// The hot loops. Each kernel exists twice: AVX2+FMA intrinsics (8 points per step, hardware
// gather from the distance map), chosen at run time when the CPU has them, and a portable
// scalar version. Both vectorise across points, never across candidates: a candidate's sum is
// computed the same way whatever batch or thread it is in, which keeps results identical for
// any thread count. Within one build and CPU the numbers are bit-for-bit reproducible.

#include "loss_kernels.hpp"

#include "thermal_lidar_calibration/core/ring_ends.hpp"

#include "float_ops.hpp"

#include "thermal_lidar_calibration/core/distance_map.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define TLC_HAVE_AVX2_PATH 1
#include <immintrin.h>
#define TLC_AVX2 __attribute__((target("avx2,fma")))
#else
#define TLC_HAVE_AVX2_PATH 0
#endif

namespace thermal_lidar_calibration {
namespace kernels {
namespace {

// A point's distance outside the crop box is capped as DistanceMap's reference rules do.
// Float->int conversions only ever see coordinates clamped into the box.
constexpr float kOffLimit = DistanceMap::kOffBoxCap;
// r^2 is clamped before the lens polynomial so it stays finite (and NaN becomes the limit):
// |x|, |y| up to 1e4, i.e. 89.99 degrees off the axis, far outside any image.
constexpr float kRadiusSquaredLimit = 2e8f;

// The map's values addressed by absolute pixel index v * width + u: saves two subtractions per
// point. Computed on integers, only ever dereferenced inside the crop.
inline const float* originOf(const MapView& map) {
  const std::ptrdiff_t offset =
      static_cast<std::ptrdiff_t>(map.y0) * map.width + static_cast<std::ptrdiff_t>(map.x0);
  return reinterpret_cast<const float*>(reinterpret_cast<std::uintptr_t>(map.values) -
                                        static_cast<std::uintptr_t>(offset) * sizeof(float));
}

const Lens kNoLens{1, 1, 0, 0, 0, 0, 0, 0, 0, 0};

// ---- scalar reference ---------------------------------------------------------------------

// Projects one point; returns false when it is behind the camera (z <= 0).
template <bool kDistorted>
inline bool projectScalar(const float* m, const Lens& lens, float px, float py, float pz,
                          float& u, float& v) {
  const float X = m[0] * px + m[1] * py + m[2] * pz + m[3];
  const float Y = m[4] * px + m[5] * py + m[6] * pz + m[7];
  const float Z = m[8] * px + m[9] * py + m[10] * pz + m[11];
  const bool front = Z > 0.0f;
  // Behind the camera (Z <= 0, including 1/0 = inf) u and v are garbage the callers never use.
  const float inv = 1.0f / Z;
  if constexpr (kDistorted) {
    const float x = X * inv, y = Y * inv;
    const float r2 = minps(x * x + y * y, kRadiusSquaredLimit);
    const float radial = 1.0f + r2 * (lens.k1 + r2 * (lens.k2 + r2 * lens.k3));
    const float xd = x * radial + 2.0f * lens.p1 * x * y + lens.p2 * (r2 + 2.0f * x * x);
    const float yd = y * radial + lens.p1 * (r2 + 2.0f * y * y) + 2.0f * lens.p2 * x * y;
    u = lens.fx * xd + lens.skew * yd + lens.cx;
    v = lens.fy * yd + lens.cy;
  } else {
    u = X * inv;
    v = Y * inv;
  }
  return front;
}

template <bool kDistorted, bool kBilinear, bool kMargin>
float sumScalar(const float* m, const Lens& lens, const Points& p, const MapView& map,
                float penalty, float margin) {
  const float* origin = originOf(map);
  float acc = 0.0f;
  for (int i = 0; i < p.count; ++i) {
    float u, v;
    const bool front = projectScalar<kDistorted>(m, lens, p.x[i], p.y[i], p.z[i], u, v);
    float d;
    if constexpr (kBilinear) {
      const float cu = clampps(u, map.x0, map.x1), cv = clampps(v, map.y0, map.y1);
      const float ix = minps(std::floor(cu), map.x1 - 1.0f);
      const float iy = minps(std::floor(cv), map.y1 - 1.0f);
      const float ax = cu - ix, ay = cv - iy;
      const float* q = origin + static_cast<int>(iy) * map.width + static_cast<int>(ix);
      const float top = q[0] + ax * (q[1] - q[0]);
      const float bottom = q[map.width] + ax * (q[map.width + 1] - q[map.width]);
      const float off = minps(std::fabs(u - cu) + std::fabs(v - cv), kOffLimit);
      d = off + (top + ay * (bottom - top));
    } else {
      const float ru = std::floor(u + 0.5f), rv = std::floor(v + 0.5f);  // ties go up
      const float cu = clampps(ru, map.x0, map.x1), cv = clampps(rv, map.y0, map.y1);
      const int index = static_cast<int>(cv) * map.width + static_cast<int>(cu);
      d = minps(std::fabs(ru - cu) + std::fabs(rv - cv), kOffLimit) + origin[index];
    }
    if constexpr (kMargin) d = maxps(d - margin, 0.0f);
    acc += front ? d : penalty;
  }
  return acc;
}

template <bool kDistorted>
int countInsideScalarImpl(const float* m, const Lens& lens, const Points& p, int width, int height) {
  int inside = 0;
  for (int i = 0; i < p.count; ++i) {
    float u, v;
    const bool front = projectScalar<kDistorted>(m, lens, p.x[i], p.y[i], p.z[i], u, v);
    const float ru = std::floor(u + 0.5f), rv = std::floor(v + 0.5f);
    inside += front && ru >= 0.0f && ru <= width - 1.0f && rv >= 0.0f && rv <= height - 1.0f;
  }
  return inside;
}

// ---- AVX2 + FMA ---------------------------------------------------------------------------
#if TLC_HAVE_AVX2_PATH

struct Avx2Projection {
  __m256 u, v, front;
};

template <bool kDistorted>
TLC_AVX2 inline Avx2Projection projectAvx2(const __m256* m, const Lens& lens, __m256 px,
                                           __m256 py, __m256 pz) {
  const __m256 X = _mm256_fmadd_ps(m[0], px, _mm256_fmadd_ps(m[1], py, _mm256_fmadd_ps(m[2], pz, m[3])));
  const __m256 Y = _mm256_fmadd_ps(m[4], px, _mm256_fmadd_ps(m[5], py, _mm256_fmadd_ps(m[6], pz, m[7])));
  const __m256 Z = _mm256_fmadd_ps(m[8], px, _mm256_fmadd_ps(m[9], py, _mm256_fmadd_ps(m[10], pz, m[11])));
  const __m256 one = _mm256_set1_ps(1.0f);
  const __m256 front = _mm256_cmp_ps(Z, _mm256_setzero_ps(), _CMP_GT_OQ);
  // Behind the camera (Z <= 0) u and v are garbage that the callers mask out.
  const __m256 inv = _mm256_div_ps(one, Z);
  __m256 u, v;
  if constexpr (kDistorted) {
    const __m256 x = _mm256_mul_ps(X, inv), y = _mm256_mul_ps(Y, inv);
    const __m256 r2 = _mm256_min_ps(_mm256_fmadd_ps(x, x, _mm256_mul_ps(y, y)),
                                    _mm256_set1_ps(kRadiusSquaredLimit));
    const __m256 poly = _mm256_fmadd_ps(r2, _mm256_set1_ps(lens.k3), _mm256_set1_ps(lens.k2));
    const __m256 radial = _mm256_fmadd_ps(
        r2, _mm256_fmadd_ps(r2, poly, _mm256_set1_ps(lens.k1)), one);
    if (lens.radial_only) {
      // p1 = p2 = skew = 0 (the FieldSAFE lens): the full formula below reduces to exactly
      // these operations (the tangential terms add an exact zero), so results are identical.
      u = _mm256_fmadd_ps(_mm256_set1_ps(lens.fx), _mm256_mul_ps(x, radial), _mm256_set1_ps(lens.cx));
      v = _mm256_fmadd_ps(_mm256_set1_ps(lens.fy), _mm256_mul_ps(y, radial), _mm256_set1_ps(lens.cy));
    } else {
      const __m256 xy2 = _mm256_mul_ps(_mm256_set1_ps(2.0f), _mm256_mul_ps(x, y));
      const __m256 two = _mm256_set1_ps(2.0f);
      const __m256 xd = _mm256_fmadd_ps(
          x, radial, _mm256_fmadd_ps(_mm256_set1_ps(lens.p1), xy2,
                                     _mm256_mul_ps(_mm256_set1_ps(lens.p2),
                                                   _mm256_fmadd_ps(two, _mm256_mul_ps(x, x), r2))));
      const __m256 yd = _mm256_fmadd_ps(
          y, radial, _mm256_fmadd_ps(_mm256_set1_ps(lens.p2), xy2,
                                     _mm256_mul_ps(_mm256_set1_ps(lens.p1),
                                                   _mm256_fmadd_ps(two, _mm256_mul_ps(y, y), r2))));
      u = _mm256_fmadd_ps(_mm256_set1_ps(lens.fx), xd,
                          _mm256_fmadd_ps(_mm256_set1_ps(lens.skew), yd, _mm256_set1_ps(lens.cx)));
      v = _mm256_fmadd_ps(_mm256_set1_ps(lens.fy), yd, _mm256_set1_ps(lens.cy));
    }
  } else {
    u = _mm256_mul_ps(X, inv);
    v = _mm256_mul_ps(Y, inv);
  }
  return {u, v, front};
}

TLC_AVX2 inline float horizontalSum(__m256 a) {
  const __m128 s = _mm_add_ps(_mm256_castps256_ps128(a), _mm256_extractf128_ps(a, 1));
  const __m128 t = _mm_add_ps(s, _mm_movehl_ps(s, s));
  return _mm_cvtss_f32(_mm_add_ss(t, _mm_shuffle_ps(t, t, 1)));
}

// Map constants broadcast once per (candidate, pair).
struct Avx2Map {
  __m256 x0, y0, x1, y1, width, last_ix, last_iy, off_limit;
  __m256i row;
  const float* origin;  // originOf(map)
};

template <bool kBilinear>
TLC_AVX2 inline __m256 distanceAvx2(const Avx2Projection& q, const Avx2Map& mv) {
  const __m256 abs_mask = _mm256_castsi256_ps(_mm256_set1_epi32(0x7fffffff));
  if constexpr (kBilinear) {
    const __m256 cu = _mm256_min_ps(_mm256_max_ps(q.u, mv.x0), mv.x1);
    const __m256 cv = _mm256_min_ps(_mm256_max_ps(q.v, mv.y0), mv.y1);
    const __m256 ix = _mm256_min_ps(_mm256_floor_ps(cu), mv.last_ix);
    const __m256 iy = _mm256_min_ps(_mm256_floor_ps(cv), mv.last_iy);
    const __m256 ax = _mm256_sub_ps(cu, ix), ay = _mm256_sub_ps(cv, iy);
    // Exact in float: pixel indices stay below 2^24 (LossEvaluator checks the image size).
    const __m256i index = _mm256_cvttps_epi32(_mm256_fmadd_ps(iy, mv.width, ix));
    const __m256i below = _mm256_add_epi32(index, mv.row);
    const __m256 v00 = _mm256_i32gather_ps(mv.origin, index, 4);
    const __m256 v01 = _mm256_i32gather_ps(mv.origin + 1, index, 4);
    const __m256 v10 = _mm256_i32gather_ps(mv.origin, below, 4);
    const __m256 v11 = _mm256_i32gather_ps(mv.origin + 1, below, 4);
    const __m256 top = _mm256_fmadd_ps(ax, _mm256_sub_ps(v01, v00), v00);
    const __m256 bottom = _mm256_fmadd_ps(ax, _mm256_sub_ps(v11, v10), v10);
    const __m256 off = _mm256_min_ps(
        _mm256_add_ps(_mm256_and_ps(_mm256_sub_ps(q.u, cu), abs_mask),
                      _mm256_and_ps(_mm256_sub_ps(q.v, cv), abs_mask)),
        mv.off_limit);
    return _mm256_add_ps(off, _mm256_fmadd_ps(ay, _mm256_sub_ps(bottom, top), top));
  } else {
    const __m256 half = _mm256_set1_ps(0.5f);
    const __m256 ru = _mm256_floor_ps(_mm256_add_ps(q.u, half));  // ties go up
    const __m256 rv = _mm256_floor_ps(_mm256_add_ps(q.v, half));
    const __m256 cu = _mm256_min_ps(_mm256_max_ps(ru, mv.x0), mv.x1);
    const __m256 cv = _mm256_min_ps(_mm256_max_ps(rv, mv.y0), mv.y1);
    // Exact in float: pixel indices stay below 2^24 (LossEvaluator checks the image size).
    const __m256i index = _mm256_cvttps_epi32(_mm256_fmadd_ps(cv, mv.width, cu));
    const __m256 off = _mm256_min_ps(
        _mm256_add_ps(_mm256_and_ps(_mm256_sub_ps(ru, cu), abs_mask),
                      _mm256_and_ps(_mm256_sub_ps(rv, cv), abs_mask)),
        mv.off_limit);
    return _mm256_add_ps(off, _mm256_i32gather_ps(mv.origin, index, 4));
  }
}

template <bool kDistorted, bool kBilinear, bool kMargin>
TLC_AVX2 float sumAvx2(const float* mp, const Lens& lens, const Points& p, const MapView& map,
                       float penalty, float margin) {
  __m256 m[12];
  for (int k = 0; k < 12; ++k) m[k] = _mm256_set1_ps(mp[k]);
  const Avx2Map mv{_mm256_set1_ps(map.x0),
                   _mm256_set1_ps(map.y0),
                   _mm256_set1_ps(map.x1),
                   _mm256_set1_ps(map.y1),
                   _mm256_set1_ps(static_cast<float>(map.width)),
                   _mm256_set1_ps(map.x1 - 1.0f),  // the crop is at least 2x2
                   _mm256_set1_ps(map.y1 - 1.0f),
                   _mm256_set1_ps(kOffLimit),
                   _mm256_set1_epi32(map.width),
                   originOf(map)};
  const __m256 pen = _mm256_set1_ps(penalty);
  const __m256 margin8 = _mm256_set1_ps(margin);
  __m256 acc = _mm256_setzero_ps();
  const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  for (int i = 0; i < p.count; i += 8) {
    const Avx2Projection q = projectAvx2<kDistorted>(m, lens, _mm256_loadu_ps(p.x + i),
                                                     _mm256_loadu_ps(p.y + i),
                                                     _mm256_loadu_ps(p.z + i));
    __m256 d = distanceAvx2<kBilinear>(q, mv);
    if constexpr (kMargin) d = _mm256_max_ps(_mm256_sub_ps(d, margin8), _mm256_setzero_ps());
    __m256 psi = _mm256_blendv_ps(pen, d, q.front);
    if (i + 8 > p.count) {
      // The last block reads the zero padding: those lanes contribute exactly zero.
      const __m256 real =
          _mm256_castsi256_ps(_mm256_cmpgt_epi32(_mm256_set1_epi32(p.count - i), lane));
      psi = _mm256_and_ps(psi, real);
    }
    acc = _mm256_add_ps(acc, psi);
  }
  return horizontalSum(acc);
}

template <bool kDistorted>
TLC_AVX2 int countInsideAvx2(const float* mp, const Lens& lens, const Points& p, int width,
                             int height) {
  __m256 m[12];
  for (int k = 0; k < 12; ++k) m[k] = _mm256_set1_ps(mp[k]);
  const __m256 half = _mm256_set1_ps(0.5f), zero = _mm256_setzero_ps();
  const __m256 max_u = _mm256_set1_ps(width - 1.0f), max_v = _mm256_set1_ps(height - 1.0f);
  int inside = 0;
  for (int i = 0; i < p.count; i += 8) {
    const Avx2Projection q = projectAvx2<kDistorted>(m, lens, _mm256_loadu_ps(p.x + i),
                                                     _mm256_loadu_ps(p.y + i),
                                                     _mm256_loadu_ps(p.z + i));
    const __m256 ru = _mm256_floor_ps(_mm256_add_ps(q.u, half));
    const __m256 rv = _mm256_floor_ps(_mm256_add_ps(q.v, half));
    __m256 ok = _mm256_and_ps(q.front, _mm256_cmp_ps(ru, zero, _CMP_GE_OQ));
    ok = _mm256_and_ps(ok, _mm256_cmp_ps(ru, max_u, _CMP_LE_OQ));
    ok = _mm256_and_ps(ok, _mm256_cmp_ps(rv, zero, _CMP_GE_OQ));
    ok = _mm256_and_ps(ok, _mm256_cmp_ps(rv, max_v, _CMP_LE_OQ));
    unsigned bits = static_cast<unsigned>(_mm256_movemask_ps(ok));
    if (i + 8 > p.count) bits &= (1u << (p.count - i)) - 1u;  // drop the padding lanes
    inside += __builtin_popcount(bits);
  }
  return inside;
}

bool cpuHasAvx2() {
  static const bool has = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  return has;
}
#endif

template <bool kDistorted, bool kBilinear, bool kMargin>
float sum(const float* m, const Lens& lens, const Points& p, const MapView& map, float penalty,
          float margin) {
#if TLC_HAVE_AVX2_PATH
  if (cpuHasAvx2()) return sumAvx2<kDistorted, kBilinear, kMargin>(m, lens, p, map, penalty, margin);
#endif
  return sumScalar<kDistorted, kBilinear, kMargin>(m, lens, p, map, penalty, margin);
}

// The eight kernels: lens or not, pixel rule, margin or not (the paper's are margin-free).
template <template <bool, bool, bool> class Kernel, typename... Args>
float dispatch(bool distorted, bool bilinear, bool margin, Args&&... args) {
  const int which = (distorted ? 4 : 0) + (bilinear ? 2 : 0) + (margin ? 1 : 0);
  switch (which) {
    case 0: return Kernel<false, false, false>::run(args...);
    case 1: return Kernel<false, false, true>::run(args...);
    case 2: return Kernel<false, true, false>::run(args...);
    case 3: return Kernel<false, true, true>::run(args...);
    case 4: return Kernel<true, false, false>::run(args...);
    case 5: return Kernel<true, false, true>::run(args...);
    case 6: return Kernel<true, true, false>::run(args...);
    default: return Kernel<true, true, true>::run(args...);
  }
}

template <bool kDistorted, bool kBilinear, bool kMargin>
struct BestSum {
  static float run(const float* m, const Lens& lens, const Points& p, const MapView& map,
                   float penalty, float margin) {
    return sum<kDistorted, kBilinear, kMargin>(m, kDistorted ? lens : kNoLens, p, map, penalty,
                                               margin);
  }
};

template <bool kDistorted, bool kBilinear, bool kMargin>
struct ScalarSum {
  static float run(const float* m, const Lens& lens, const Points& p, const MapView& map,
                   float penalty, float margin) {
    return sumScalar<kDistorted, kBilinear, kMargin>(m, kDistorted ? lens : kNoLens, p, map,
                                                     penalty, margin);
  }
};

}  // namespace

bool vectorPathActive() {
#if TLC_HAVE_AVX2_PATH
  return cpuHasAvx2();
#else
  return false;
#endif
}

float sumPsi(const float* m, bool distorted, bool bilinear, const Lens& lens, const Points& p,
             const MapView& map, float penalty, float margin) {
  return dispatch<BestSum>(distorted, bilinear, margin > 0.0f, m, lens, p, map, penalty, margin);
}

int countInside(const float* m, bool distorted, const Lens& lens, const Points& p, int width,
                int height) {
#if TLC_HAVE_AVX2_PATH
  if (cpuHasAvx2()) {
    return distorted ? countInsideAvx2<true>(m, lens, p, width, height)
                     : countInsideAvx2<false>(m, kNoLens, p, width, height);
  }
#endif
  return countInsideScalar(m, distorted, lens, p, width, height);
}

float sumPsiScalar(const float* m, bool distorted, bool bilinear, const Lens& lens,
                   const Points& p, const MapView& map, float penalty, float margin) {
  return dispatch<ScalarSum>(distorted, bilinear, margin > 0.0f, m, lens, p, map, penalty,
                             margin);
}

int countInsideScalar(const float* m, bool distorted, const Lens& lens, const Points& p,
                      int width, int height) {
  return distorted ? countInsideScalarImpl<true>(m, lens, p, width, height)
                   : countInsideScalarImpl<false>(m, kNoLens, p, width, height);
}

bool atLeastInside(const float* m, bool distorted, const Lens& lens, const Points& p, int width,
                   int height, int needed) {
  if (needed <= 0) return true;
  constexpr int kChunk = 16;  // decide every 16 points: cheap enough, exits early on most poses
  int inside = 0;
  for (int begin = 0; begin < p.count; begin += kChunk) {
    const Points chunk{p.x + begin, p.y + begin, p.z + begin, std::min(kChunk, p.count - begin)};
    inside += countInside(m, distorted, lens, chunk, width, height);
    if (inside >= needed) return true;
    if (inside + (p.count - begin - chunk.count) < needed) return false;
  }
  return inside >= needed;
}

namespace {

template <bool kDistorted>
void ringEndOffsetsScalarImpl(const float* m, const Lens& lens, const RingEnds& e, float* out) {
  for (int i = 0; i < e.count; ++i) {
    float u, v;
    out[i] = projectScalar<kDistorted>(m, lens, e.x[i], e.y[i], e.z[i], u, v)
                 ? ringEndOffset(e.edges + e.offset[i], e.rows[i], static_cast<int>(e.first_row[i]),
                                 static_cast<int>(e.side[i]), u, v, e.half_step[i])
                 : std::numeric_limits<float>::quiet_NaN();
  }
}

#if TLC_HAVE_AVX2_PATH
// ringEndOffset on 8 ends at a time: the outline's two rows around each end gathered from the
// pair's columns (masked where a row lies outside the outline).
// Same operations in the same order as the scalar code, lane by lane.
template <bool kDistorted>
TLC_AVX2 void ringEndOffsetsAvx2(const float* mp, const Lens& lens, const RingEnds& e, float* out) {
  __m256 m[12];
  for (int k = 0; k < 12; ++k) m[k] = _mm256_set1_ps(mp[k]);
  const __m256 one = _mm256_set1_ps(1.0f), minus_one = _mm256_set1_ps(-1.0f), zero = _mm256_setzero_ps();
  const __m256 nan = _mm256_set1_ps(std::numeric_limits<float>::quiet_NaN());
  for (int i = 0; i < e.count; i += 8) {
    const Avx2Projection q = projectAvx2<kDistorted>(m, lens, _mm256_loadu_ps(e.x + i), _mm256_loadu_ps(e.y + i),
                                                     _mm256_loadu_ps(e.z + i));
    const __m256 rows = _mm256_cvtepi32_ps(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(e.rows + i)));
    const __m256 f = _mm256_sub_ps(q.v, _mm256_loadu_ps(e.first_row + i));
    __m256 ok = _mm256_and_ps(q.front, _mm256_cmp_ps(f, minus_one, _CMP_GE_OQ));
    ok = _mm256_and_ps(ok, _mm256_cmp_ps(f, rows, _CMP_LT_OQ));
    ok = _mm256_and_ps(ok, _mm256_cmp_ps(q.u, q.u, _CMP_ORD_Q));
    // Clamped so that lanes left out still convert to a small index (max_ps returns -1 for NaN).
    // On the lanes kept it changes only the last row's weight, where the row below is not read.
    const __m256 fc = _mm256_min_ps(_mm256_max_ps(f, minus_one), _mm256_sub_ps(rows, one));
    const __m256 r = _mm256_floor_ps(fc);
    const __m256 a = _mm256_sub_ps(fc, r);
    const __m256i at = _mm256_add_epi32(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(e.offset + i)),
                                        _mm256_cvttps_epi32(r));
    const __m256 has0 = _mm256_and_ps(ok, _mm256_cmp_ps(r, zero, _CMP_GE_OQ));
    const __m256 has1 = _mm256_and_ps(ok, _mm256_cmp_ps(_mm256_add_ps(r, one), rows, _CMP_LT_OQ));
    const __m256 e0 = _mm256_mask_i32gather_ps(nan, e.edges, at, has0, 4);
    const __m256 e1 = _mm256_mask_i32gather_ps(nan, e.edges + 1, at, has1, 4);
    const __m256 fin0 = _mm256_cmp_ps(e0, e0, _CMP_ORD_Q), fin1 = _mm256_cmp_ps(e1, e1, _CMP_ORD_Q);
    const __m256 between = _mm256_add_ps(e0, _mm256_mul_ps(a, _mm256_sub_ps(e1, e0)));
    const __m256 column = _mm256_blendv_ps(_mm256_blendv_ps(e1, e0, fin0), between, _mm256_and_ps(fin0, fin1));
    const __m256 beyond = _mm256_mul_ps(_mm256_loadu_ps(e.side + i), _mm256_sub_ps(q.u, column));
    const __m256 offset = _mm256_add_ps(beyond, _mm256_loadu_ps(e.half_step + i));
    _mm256_storeu_ps(out + i, _mm256_blendv_ps(nan, offset, _mm256_and_ps(ok, _mm256_or_ps(fin0, fin1))));
  }
}
#endif

// In the ends' order: a ring whose two ends are both measured costs its middle's offset and its
// width's, the other ends their own offset (ring_ends.hpp, ringPairCost).
float combineRingEnds(const float* offset, const std::uint8_t* pairs_previous, int count, float cap,
                      float width_weight) {
  float sum = 0.0f;
  for (int i = 0; i < count; ++i) {
    if (i + 1 < count && pairs_previous[i + 1] != 0 && offset[i] == offset[i] && offset[i + 1] == offset[i + 1]) {
      sum += ringPairCost(offset[i], offset[i + 1], cap, width_weight);
      ++i;
    } else {
      sum += ringEndCharge(offset[i], cap);
    }
  }
  return sum;
}

// One pair's ends' signed offsets at a time, a buffer per thread: the loss runs candidates in parallel.
std::vector<float>& offsetBuffer(int count) {
  thread_local std::vector<float> buffer;
  const std::size_t padded = static_cast<std::size_t>((count + kPointBlock - 1) / kPointBlock * kPointBlock);
  if (buffer.size() < padded) buffer.resize(padded);
  return buffer;
}

}  // namespace

float sumRingEnds(const float* m, bool distorted, const Lens& lens, const RingEnds& ends, float cap,
                  float width_weight) {
#if TLC_HAVE_AVX2_PATH
  if (cpuHasAvx2()) {
    float* offset = offsetBuffer(ends.count).data();
    distorted ? ringEndOffsetsAvx2<true>(m, lens, ends, offset) : ringEndOffsetsAvx2<false>(m, kNoLens, ends, offset);
    return combineRingEnds(offset, ends.pairs_previous, ends.count, cap, width_weight);
  }
#endif
  return sumRingEndsScalar(m, distorted, lens, ends, cap, width_weight);
}

float sumRingEndsScalar(const float* m, bool distorted, const Lens& lens, const RingEnds& ends, float cap,
                        float width_weight) {
  float* offset = offsetBuffer(ends.count).data();
  distorted ? ringEndOffsetsScalarImpl<true>(m, lens, ends, offset)
            : ringEndOffsetsScalarImpl<false>(m, kNoLens, ends, offset);
  return combineRingEnds(offset, ends.pairs_previous, ends.count, cap, width_weight);
}

bool projectPoint(const float* m, bool distorted, const Lens& lens, float x, float y, float z, float& u,
                  float& v) {
  return distorted ? projectScalar<true>(m, lens, x, y, z, u, v) : projectScalar<false>(m, kNoLens, x, y, z, u, v);
}

}  // namespace kernels
}  // namespace thermal_lidar_calibration
