// The ground-plane size check: people's height in the image grows with how far below the horizon
// their feet are; the model learns that line from recent candidates and flags what is much
// shorter than a person at its foot row.

#include "thermal_lidar_calibration/detection/person_size_model.hpp"

#include "../support/thermal_scene.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace thermal_lidar_calibration {
namespace detection {
namespace {

// A camera whose horizon is at row 50, people 1.1x as tall (px) as their feet are below it.
constexpr double kHorizon = 50.0;
constexpr double kSlope = 1.1;

// A box `scale` times a person's height standing with its feet at `foot` (width a third).
cv::Rect standing(double foot, double scale) {
  const int h = static_cast<int>(std::lround(scale * kSlope * (foot - kHorizon)));
  return cv::Rect(300, static_cast<int>(foot) - h, std::max(1, h / 3), h);
}

// Frame k: three people at different distances, heights varying +-10 % (walking, build), and
// every `animal_every`-th frame an animal end on (half a person's height).
std::vector<cv::Rect> frame(int k, int animal_every = 0) {
  std::vector<cv::Rect> boxes;
  for (int i = 0; i < 3; ++i) {
    const double foot = 70.0 + std::fmod(37.0 * k + 113.0 * i, 400.0);
    boxes.push_back(standing(foot, 1.0 + 0.1 * std::sin(1.7 * k + i)));
  }
  if (animal_every > 0 && k % animal_every == 0) boxes.push_back(standing(90.0 + std::fmod(53.0 * k, 300.0), 0.5));
  return boxes;
}

TEST(PersonSizeModel, LearnsTheHorizonAndSlopeFromPeopleAtManyDistances) {
  PersonSizeModel model;
  for (int k = 0; k < 100; ++k) model.observe(frame(k));
  ASSERT_TRUE(model.fit());
  EXPECT_NEAR(model.fit()->horizon_row, kHorizon, 8.0);
  EXPECT_NEAR(model.fit()->slope, kSlope, 0.1 * kSlope);
  EXPECT_EQ(model.fit()->samples, 300);
  EXPECT_GE(model.fit()->support, 270);
}

TEST(PersonSizeModel, FlagsWhatIsHalfAPersonTallAtItsFootRowAndNothingTaller) {
  PersonSizeModel model;
  for (int k = 0; k < 100; ++k) model.observe(frame(k, 3));  // a quarter of the candidates are animals
  ASSERT_TRUE(model.fit());
  EXPECT_NEAR(model.fit()->horizon_row, kHorizon, 8.0);  // the people's line, not the animals'
  for (double foot : {100.0, 250.0, 420.0}) {
    EXPECT_TRUE(model.tooShortForItsRange(standing(foot, 0.5))) << "animal, feet at row " << foot;
    EXPECT_FALSE(model.tooShortForItsRange(standing(foot, 0.85))) << "short person, feet at row " << foot;
    EXPECT_FALSE(model.tooShortForItsRange(standing(foot, 1.6))) << "tall thing, feet at row " << foot;
  }
  // Feet at or above the horizon: nothing to judge from.
  EXPECT_FALSE(model.heightRatio(cv::Rect(300, 20, 5, 30)));
}

TEST(PersonSizeModel, StaysUnreadyWithTooFewCandidatesOneDistanceOrTheCheckOff) {
  PersonSizeModel model;
  for (int k = 0; k < 15; ++k) model.observe(frame(k));  // 45 candidates < 60
  EXPECT_FALSE(model.fit());
  EXPECT_FALSE(model.tooShortForItsRange(standing(200.0, 0.3)));

  PersonSizeModel one_distance;  // the horizon cannot be placed from one foot row
  for (int k = 0; k < 100; ++k) one_distance.observe({standing(200.0, 1.0 + 0.05 * std::sin(k))});
  EXPECT_FALSE(one_distance.fit());

  ThermalSegmenterConfig off;
  off.size_history = 0;
  PersonSizeModel disabled(off);
  for (int k = 0; k < 100; ++k) disabled.observe(frame(k));
  EXPECT_FALSE(disabled.fit());
}

TEST(PersonSizeModel, SameFramesInSameOrderGiveTheSameFit) {
  PersonSizeModel a, b;
  for (int k = 0; k < 80; ++k) {
    a.observe(frame(k, 4));
    b.observe(frame(k, 4));
  }
  ASSERT_TRUE(a.fit() && b.fit());
  EXPECT_EQ(a.fit()->horizon_row, b.fit()->horizon_row);
  EXPECT_EQ(a.fit()->slope, b.fit()->slope);
}

TEST(PersonSizeModel, ApplySizeCheckDropsTheAnimalFromTheMaskAndRenumbers) {
  PersonSizeModel model;
  for (int k = 0; k < 100; ++k) model.observe(frame(k));
  ASSERT_TRUE(model.fit());
  // A frame from the segmenter: person (id 1), animal end on (id 2), person (id 3).
  ThermalSegmentation seg;
  seg.mask = cv::Mat::zeros(512, 640, CV_8UC1);
  const cv::Rect boxes[] = {standing(300.0, 1.0) + cv::Point(-200, 0), standing(300.0, 0.5),
                            standing(200.0, 0.95) + cv::Point(200, 0)};
  for (int i = 0; i < 3; ++i) {
    ThermalPerson p;
    p.id = i + 1;
    p.bbox = boxes[i];
    p.area_px = boxes[i].area();
    seg.mask(boxes[i]).setTo(cv::Scalar(p.id));
    seg.people.push_back(p);
  }
  applySizeCheck(seg, model);
  ASSERT_EQ(seg.people.size(), 2u);
  EXPECT_EQ(seg.people[0].bbox, boxes[0]);
  EXPECT_EQ(seg.people[1].bbox, boxes[2]);
  EXPECT_EQ(seg.people[1].id, 2);
  EXPECT_EQ(cv::countNonZero(seg.mask == 1), boxes[0].area());
  EXPECT_EQ(cv::countNonZero(seg.mask == 2), boxes[2].area());
  EXPECT_EQ(cv::countNonZero(seg.mask == 3), 0);
  EXPECT_EQ(cv::countNonZero(seg.mask(boxes[1])), 0);
  ASSERT_EQ(seg.rejected.size(), 1u);
  EXPECT_EQ(seg.rejected[0].reason, "too_short_for_range");
}

TEST(PersonSizeModel, ConfigurationKeysAreValidated) {
  ThermalSegmenterConfig c;
  c.size_min_ratio = 1.5;
  EXPECT_THROW(c.validate(), std::invalid_argument);
  c = ThermalSegmenterConfig();
  c.size_history = -1;
  EXPECT_THROW(c.validate(), std::invalid_argument);
  c = ThermalSegmenterConfig();
  c.size_min_samples = 5;
  EXPECT_THROW(c.validate(), std::invalid_argument);
}

}  // namespace
}  // namespace detection
}  // namespace thermal_lidar_calibration
