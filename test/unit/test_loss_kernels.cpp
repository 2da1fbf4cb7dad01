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
  // On this CPU the dispatched code is the AVX2 one; the fallback serves CPUs without it. They
  // differ only by FMA rounding, which can move a point across a pixel boundary now and then.
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
       kernels::sumPsiNearestPinhole(pinhole, pts, view, 3200.0f), 2.0f);
  near(kernels::sumPsiScalar(pinhole, false, true, lens, pts, view, 3200.0f),
       kernels::sumPsiBilinearPinhole(pinhole, pts, view, 3200.0f), 0.05f);
  near(kernels::sumPsiScalar(m, true, false, lens, pts, view, 3200.0f),
       kernels::sumPsiNearestDistorted(m, lens, pts, view, 3200.0f), 2.0f);
  near(kernels::sumPsiScalar(m, true, true, lens, pts, view, 3200.0f),
       kernels::sumPsiBilinearDistorted(m, lens, pts, view, 3200.0f), 0.05f);
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
  EXPECT_EQ(kernels::sumPsiNearestDistorted(m, full, points, view, 3200.0f),
            kernels::sumPsiNearestDistorted(m, radial, points, view, 3200.0f));
  EXPECT_EQ(kernels::sumPsiBilinearDistorted(m, full, points, view, 3200.0f),
            kernels::sumPsiBilinearDistorted(m, radial, points, view, 3200.0f));
  EXPECT_EQ(kernels::countInside(m, true, full, points, 640, 512),
            kernels::countInside(m, true, radial, points, 640, 512));
}
