// The kernels' fast paths must give the same numbers as the general ones.
#include "../../src/core/loss_kernels.hpp"

#include "thermal_lidar_calibration/core/distance_map.hpp"
#include "thermal_lidar_calibration/core/random.hpp"

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
