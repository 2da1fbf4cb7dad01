// The kernels' fast paths must give the same numbers as the general ones.
#include "../../src/core/loss_kernels.hpp"

#include "thermal_lidar_calibration/core/distance_map.hpp"
#include "thermal_lidar_calibration/core/random.hpp"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

using namespace thermal_lidar_calibration;

TEST(LossKernels, RadialOnlyLensPathIsBitIdenticalToTheFullFormula) {
  cv::Mat mask = cv::Mat::zeros(512, 640, CV_8UC1);
  cv::rectangle(mask, cv::Rect(300, 100, 30, 120), cv::Scalar(1), cv::FILLED);
  const DistanceMap map(mask);
  const kernels::MapView view{map.data(), map.width(), float(map.x0()), float(map.y0()),
                              float(map.x0() + map.width() - 1), float(map.y0() + map.height() - 1)};
  Rng rng(9);
  std::vector<float> x, y, z;
  for (int i = 0; i < 203; ++i) {  // not a multiple of 8: the padded tail is covered too
    x.push_back(float(rng.uniform(-4, 4)));
    y.push_back(float(rng.uniform(-3, 3)));
    z.push_back(float(rng.uniform(-2, 20)));
  }
  const int count = int(x.size());
  x.resize(208, 0.0f);  // the kernels read whole blocks of 8: pad as PreparedPair does
  y.resize(208, 0.0f);
  z.resize(208, 0.0f);
  const kernels::Points points{x.data(), y.data(), z.data(), count};
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
