// The kernels' fast paths must give the same numbers as the general ones.
#include "../../src/core/loss_kernels.hpp"

#include "thermal_lidar_calibration/core/distance_map.hpp"
#include "thermal_lidar_calibration/core/random.hpp"
#include "thermal_lidar_calibration/core/ring_ends.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

using namespace thermal_lidar_calibration;

namespace {

struct KernelData {
  DistanceMap map;
  std::vector<float> x, y, z;
  int count = 0;
  KernelData() : map(makeMask()) {
    Rng rng(9);
    for (int i = 0; i < 203; ++i) {  // not a multiple of 8: the padded tail is covered too
      x.push_back(float(rng.uniform(-4, 4)));
      y.push_back(float(rng.uniform(-3, 3)));
      z.push_back(float(rng.uniform(-2, 20)));
    }
    count = int(x.size());
    x.resize(208, 0.0f);  // the kernels read whole blocks of 8: pad as PreparedPair does
    y.resize(208, 0.0f);
    z.resize(208, 0.0f);
  }
  static cv::Mat makeMask() {
    cv::Mat mask = cv::Mat::zeros(512, 640, CV_8UC1);
    cv::rectangle(mask, cv::Rect(300, 100, 30, 120), cv::Scalar(1), cv::FILLED);
    return mask;
  }
  kernels::MapView view() const {
    return {map.data(), map.width(), float(map.x0()), float(map.y0()),
            float(map.x0() + map.width() - 1), float(map.y0() + map.height() - 1)};
  }
  kernels::Points points() const { return {x.data(), y.data(), z.data(), count}; }
};

}  // namespace

TEST(LossKernels, PortableFallbackAgreesWithTheDispatchedCode) {
  // The dispatched code is the AVX2 one where the CPU has it; the fallback serves CPUs without
  // it. They differ only by FMA rounding, which can move a point across a pixel boundary now and
  // then. Without AVX2 both calls run the fallback: nothing to compare, so say so.
  if (!kernels::vectorPathActive()) GTEST_SKIP() << "this CPU has no AVX2+FMA: the vector kernels cannot run here";
  const KernelData d;
  const float m[12] = {0.99f, 0.01f, -0.02f, 0.1f, -0.01f, 0.98f, 0.05f, -0.2f, 0.02f, -0.05f, 0.99f, 0.3f};
  const float pinhole[12] = {772.0f * m[0] + 322.0f * m[8], 772.0f * m[1] + 322.0f * m[9],
                             772.0f * m[2] + 322.0f * m[10], 772.0f * m[3] + 322.0f * m[11],
                             772.0f * m[4] + 250.0f * m[8], 772.0f * m[5] + 250.0f * m[9],
                             772.0f * m[6] + 250.0f * m[10], 772.0f * m[7] + 250.0f * m[11],
                             m[8], m[9], m[10], m[11]};
  const kernels::Lens lens{772.41f, 772.83f, 322.67f, 250.66f, 0.0f, -0.0496f, 0.3632f, 0.001f, -0.002f, 0.01f};
  const auto pts = d.points();
  const auto view = d.view();
  // Sums reach ~1e7 px (points far off the image), so the tolerance is relative plus a pixel or two.
  const auto near = [](float a, float b, float pixels) {
    EXPECT_NEAR(a, b, pixels + 1e-5f * std::fabs(b));
  };
  near(kernels::sumPsiScalar(pinhole, false, false, lens, pts, view, 3200.0f),
       kernels::sumPsi(pinhole, false, false, lens, pts, view, 3200.0f), 2.0f);
  near(kernels::sumPsiScalar(pinhole, false, true, lens, pts, view, 3200.0f),
       kernels::sumPsi(pinhole, false, true, lens, pts, view, 3200.0f), 0.05f);
  near(kernels::sumPsiScalar(m, true, false, lens, pts, view, 3200.0f),
       kernels::sumPsi(m, true, false, lens, pts, view, 3200.0f), 2.0f);
  near(kernels::sumPsiScalar(m, true, true, lens, pts, view, 3200.0f),
       kernels::sumPsi(m, true, true, lens, pts, view, 3200.0f), 0.05f);
  near(kernels::sumPsiScalar(m, true, true, lens, pts, view, 3200.0f, 1.0f),  // with a margin
       kernels::sumPsi(m, true, true, lens, pts, view, 3200.0f, 1.0f), 0.05f);
  near(kernels::sumPsiScalar(pinhole, false, false, lens, pts, view, 3200.0f, 1.0f),
       kernels::sumPsi(pinhole, false, false, lens, pts, view, 3200.0f, 1.0f), 2.0f);
  EXPECT_NEAR(kernels::countInsideScalar(m, true, lens, pts, 640, 512),
              kernels::countInside(m, true, lens, pts, 640, 512), 1);
  EXPECT_GT(kernels::countInside(m, true, lens, pts, 640, 512), 0);  // the data reaches the image
}

TEST(LossKernels, RadialOnlyLensPathIsBitIdenticalToTheFullFormula) {
  const KernelData d;
  const kernels::MapView view = d.view();
  const kernels::Points points = d.points();
  const float m[12] = {0.99f, 0.01f, -0.02f, 0.1f, -0.01f, 0.98f, 0.05f, -0.2f, 0.02f, -0.05f, 0.99f, 0.3f};
  kernels::Lens full{772.41f, 772.83f, 322.67f, 250.66f, 0.0f, -0.0496f, 0.3632f, 0.0f, 0.0f, 0.01f};
  kernels::Lens radial = full;
  radial.radial_only = true;
  EXPECT_EQ(kernels::sumPsi(m, true, false, full, points, view, 3200.0f),
            kernels::sumPsi(m, true, false, radial, points, view, 3200.0f));
  EXPECT_EQ(kernels::sumPsi(m, true, true, full, points, view, 3200.0f),
            kernels::sumPsi(m, true, true, radial, points, view, 3200.0f));
  EXPECT_EQ(kernels::countInside(m, true, full, points, 640, 512),
            kernels::countInside(m, true, radial, points, 640, 512));
}

TEST(LossKernels, ProjectionsAtTheCameraPlaneCostTheCapOrThePenaltyInEveryKernel) {
  // Z -> 0+ makes u, v infinite, or NaN when X = 0 too (0 * inf). Such a point must still cost
  // a finite amount (the 2e6 px cap plus the map value at the box corner it is clamped to), in
  // the vector code and the portable code alike; Z <= 0 costs the penalty. (Without AVX2 the
  // "vector" calls run the portable code: the cost checks still hold, the comparison is moot.)
  const KernelData d;
  const kernels::MapView view = d.view();
  const float pinhole[12] = {772, 0, 322, 0, 0, 772, 250, 0, 0, 0, 1, 0};  // K [I | 0]
  const float extrinsic[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
  const kernels::Lens lens{772.41f, 772.83f, 322.67f, 250.66f, 0.0f, -0.0496f, 0.3632f, 0.001f, -0.002f, 0.01f};
  const float cap = 2e6f, penalty = 3200.0f;
  const float diagonal = view.x1 - view.x0 + view.y1 - view.y0;  // bounds any map value
  struct Case {
    float x, y, z;
    bool behind;
  };
  const Case cases[] = {{1, 1, 0.0f, true},        {1, 1, -1e-42f, true},  {1, -1, 1e-42f, false},
                        {0, 0, 1e-42f, false},     {-1, 1, 1e-30f, false}, {0, 3, 1e-39f, false}};
  for (const Case& c : cases) {
    std::vector<float> x(8, 0.0f), y(8, 0.0f), z(8, 0.0f);
    x[0] = c.x;
    y[0] = c.y;
    z[0] = c.z;
    const kernels::Points one{x.data(), y.data(), z.data(), 1};
    const std::string what = "point (" + std::to_string(c.x) + ", " + std::to_string(c.y) + ", " +
                             std::to_string(c.z) + ")";
    for (int distorted = 0; distorted < 2; ++distorted) {
      for (int bilinear = 0; bilinear < 2; ++bilinear) {
        const float* m = distorted ? extrinsic : pinhole;
        const float scalar = kernels::sumPsiScalar(m, distorted, bilinear, lens, one, view, penalty);
        const float vector = kernels::sumPsi(m, distorted, bilinear, lens, one, view, penalty);
        SCOPED_TRACE(what + (distorted ? ", distorted" : ", pinhole") +
                     (bilinear ? ", bilinear" : ", nearest"));
        EXPECT_EQ(scalar, vector);
        if (c.behind) {
          EXPECT_EQ(vector, penalty);
        } else {
          EXPECT_GE(vector, cap);
          EXPECT_LE(vector, cap + diagonal);
        }
        EXPECT_EQ(kernels::countInside(m, distorted, lens, one, 640, 512), 0);
        EXPECT_EQ(kernels::countInsideScalar(m, distorted, lens, one, 640, 512), 0);
      }
    }
  }
}

TEST(LossKernels, RingEndKernelsAgreeWithRingEndCostEndByEnd) {
  // Ends at random points, each with an outline of random rows around where it projects (some
  // rows without a column, some ends beyond the outline's rows or behind the camera); 203 ends,
  // so the padded tail is covered. Each end's cost from the portable and the dispatched kernel
  // against ringEndCost on the same pixel; their sums against the sum of the ends; then the same
  // ends taken two by two as rings, against ringPairCost.
  const KernelData d;
  const float m[12] = {0.99f, 0.01f, -0.02f, 0.1f, -0.01f, 0.98f, 0.05f, -0.2f, 0.02f, -0.05f, 0.99f, 0.3f};
  const float pinhole[12] = {772, 0, 322, 0, 0, 772, 250, 0, 0, 0, 1, 0};
  const kernels::Lens lens{772.41f, 772.83f, 322.67f, 250.66f, 0.0f, -0.0496f, 0.3632f, 0.001f, -0.002f, 0.01f};
  const float cap = 3.0f;
  Rng rng(4);
  for (int distorted = 0; distorted < 2; ++distorted) {
    SCOPED_TRACE(distorted ? "distorted" : "pinhole");
    const float* mp = distorted ? m : pinhole;
    std::vector<std::int32_t> rows, offset;
    std::vector<float> x, y, z, side, first_row, half_step, edges, expected;
    int cap_ends = 0, inside_ends = 0;
    for (int i = 0; i < 203; ++i) {
      // Points behind the camera or near the image (far off it, float rounding reaches 0.01 px).
      int k = 0;
      float u = 0.0f, v = 0.0f;
      bool front = false;
      do {
        k = int(rng.uniform(0, d.count - 1e-9));
        front = kernels::projectPoint(mp, distorted, lens, d.x[k], d.y[k], d.z[k], u, v);
      } while (front && !(u > -50.0f && u < 690.0f && v > -50.0f && v < 562.0f));
      PersonOutline o;
      const int n = int(rng.uniform(0, 40));
      o.first_row = int(std::floor(v)) - int(rng.uniform(-10, 30));
      for (int r = 0; r < n; ++r) {
        const bool none = rng.uniform(0, 1) < 0.2;
        o.left.push_back(none ? std::nanf("") : u + float(rng.uniform(-2, 2)));  // within the cap
      }
      o.right = o.left;
      const int s = rng.uniform(0, 1) < 0.5 ? -1 : 1;
      const float h = float(rng.uniform(0, 1));
      x.push_back(d.x[k]);
      y.push_back(d.y[k]);
      z.push_back(d.z[k]);
      side.push_back(float(s));
      first_row.push_back(float(o.first_row));
      rows.push_back(n);
      offset.push_back(std::int32_t(edges.size()));
      half_step.push_back(h);
      edges.insert(edges.end(), o.left.begin(), o.left.end());
      const float cost = front ? ringEndCost(o, s, u, v, h, cap) : cap;
      expected.push_back(cost);
      (cost == cap ? cap_ends : inside_ends) += 1;
    }
    ASSERT_GT(cap_ends, 10);  // both kinds of end are exercised
    ASSERT_GT(inside_ends, 50);
    const int count = int(x.size());
    x.resize(208, 0.0f);
    y.resize(208, 0.0f);
    z.resize(208, 0.0f);
    rows.resize(208, 0);
    offset.resize(208, 0);
    side.resize(208, 1.0f);
    first_row.resize(208, 0.0f);
    half_step.resize(208, 0.0f);
    const std::vector<std::uint8_t> alone(208, 0);  // no end paired with the one before it
    double total = 0.0, vector_total = 0.0;
    for (int i = 0; i < count; ++i) {
      // One end at a time: its fields copied into arrays of one block.
      std::vector<std::int32_t> r1(8, 0), o1(8, 0);
      std::vector<float> x1(8, 0.0f), y1(8, 0.0f), z1(8, 0.0f), s1(8, 1.0f), f1(8, 0.0f), h1(8, 0.0f);
      x1[0] = x[i], y1[0] = y[i], z1[0] = z[i];
      r1[0] = rows[i], o1[0] = offset[i], s1[0] = side[i], f1[0] = first_row[i], h1[0] = half_step[i];
      const kernels::RingEnds one{x1.data(), y1.data(), z1.data(), s1.data(),    f1.data(),
                                  r1.data(), o1.data(), h1.data(), edges.data(), alone.data(), 1};
      SCOPED_TRACE("end " + std::to_string(i));
      // The vector projection rounds differently (FMA): near a row boundary with a missing row the
      // outline jumps, so compare only ends more than 0.01 px from one.
      float u, v;
      kernels::projectPoint(mp, distorted, lens, x[i], y[i], z[i], u, v);
      const bool at_boundary = std::fabs(v - std::round(v)) < 0.01f;
      EXPECT_FLOAT_EQ(kernels::sumRingEndsScalar(mp, distorted, lens, one, cap, 0.5f), expected[i]);
      const float vector = kernels::sumRingEnds(mp, distorted, lens, one, cap, 0.5f);
      if (!at_boundary) EXPECT_NEAR(vector, expected[i], 1e-3);
      total += expected[i];
      vector_total += vector;
    }
    const kernels::RingEnds all{x.data(),      y.data(),         z.data(),     side.data(),  first_row.data(),
                                rows.data(), offset.data(), half_step.data(), edges.data(), alone.data(), count};
    EXPECT_NEAR(kernels::sumRingEndsScalar(mp, distorted, lens, all, cap, 0.5f), total, 1e-3);
    // All ends at once: the same as one at a time (the padding lanes add nothing).
    EXPECT_NEAR(kernels::sumRingEnds(mp, distorted, lens, all, cap, 0.5f), vector_total, 1e-3);

    // Every end paired with the one before it (ends 2k and 2k+1 as one ring): each pair costs
    // ringPairCost of the two offsets when both are measured, else the two ends' own costs.
    std::vector<std::uint8_t> paired(208, 0);
    for (int i = 1; i < count; i += 2) paired[i] = 1;
    double pair_total = 0.0, vector_pairs = 0.0;
    for (int i = 0; i < count; i += 2) {
      const auto offsetOf = [&](int k) {
        float u, v;
        return kernels::projectPoint(mp, distorted, lens, x[k], y[k], z[k], u, v)
                   ? ringEndOffset(edges.data() + offset[k], rows[k], int(first_row[k]), int(side[k]), u, v,
                                   half_step[k])
                   : std::nanf("");
      };
      const float a = offsetOf(i);
      const float b = i + 1 < count ? offsetOf(i + 1) : std::nanf("");
      if (i + 1 < count && a == a && b == b) {
        pair_total += ringPairCost(a, b, cap, 0.5f);
      } else {
        pair_total += expected[i] + (i + 1 < count ? expected[i + 1] : 0.0f);
      }
      const int n = std::min(2, count - i);
      std::vector<std::int32_t> r2(8, 0), o2(8, 0);
      std::vector<float> x2(8, 0.0f), y2(8, 0.0f), z2(8, 0.0f), s2(8, 1.0f), f2(8, 0.0f), h2(8, 0.0f);
      std::vector<std::uint8_t> p2(8, 0);
      for (int k = 0; k < n; ++k) {
        x2[k] = x[i + k], y2[k] = y[i + k], z2[k] = z[i + k], r2[k] = rows[i + k], o2[k] = offset[i + k];
        s2[k] = side[i + k], f2[k] = first_row[i + k], h2[k] = half_step[i + k], p2[k] = paired[i + k];
      }
      const kernels::RingEnds two{x2.data(), y2.data(), z2.data(), s2.data(),    f2.data(),
                                  r2.data(), o2.data(), h2.data(), edges.data(), p2.data(), n};
      vector_pairs += kernels::sumRingEnds(mp, distorted, lens, two, cap, 0.5f);
    }
    const kernels::RingEnds rings{x.data(),      y.data(),         z.data(),     side.data(),   first_row.data(),
                                  rows.data(), offset.data(), half_step.data(), edges.data(), paired.data(), count};
    EXPECT_NEAR(kernels::sumRingEndsScalar(mp, distorted, lens, rings, cap, 0.5f), pair_total, 1e-3);
    EXPECT_NEAR(kernels::sumRingEnds(mp, distorted, lens, rings, cap, 0.5f), vector_pairs, 1e-3);
    EXPECT_GT(std::fabs(pair_total - total), 1.0) << "pairing should change the sum";
  }
}
