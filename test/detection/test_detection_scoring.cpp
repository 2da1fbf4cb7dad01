// The detection-quality scorer: mask instances matched at IoU >= 0.5, clusters at >= 80 % of
// their points on one person, people who are not scored ignored, per-frame count agreement.

#include "thermal_lidar_calibration/detection/detection_scoring.hpp"

#include "../support/test_files.hpp"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

namespace thermal_lidar_calibration {
namespace {

using detection::DetectionScore;
using detection::FrameScore;
using detection::scoreClusters;
using detection::scoreMask;
using detection::TruthPerson;

cv::Mat truthImage() {
  cv::Mat ids = cv::Mat::zeros(100, 200, CV_16UC1);
  ids(cv::Rect(10, 10, 20, 60)).setTo(1);   // scored
  ids(cv::Rect(60, 10, 20, 60)).setTo(2);   // scored
  ids(cv::Rect(110, 10, 20, 60)).setTo(3);  // present, not scored (too far, say)
  return ids;
}
const std::vector<TruthPerson> kPeople = {{1, true}, {2, true}, {3, false}};

TEST(ScoreMask, MatchesAtIouHalfAndIgnoresPeopleWhoAreNotScored) {
  const cv::Mat truth = truthImage();
  cv::Mat mask = cv::Mat::zeros(truth.size(), CV_8UC1);
  mask(cv::Rect(10, 12, 20, 58)).setTo(1);   // person 1, IoU 58/60: true positive
  mask(cv::Rect(60, 10, 20, 24)).setTo(2);   // top 40 % of person 2: IoU 0.4, a false positive
  mask(cv::Rect(110, 10, 20, 60)).setTo(3);  // person 3: not scored, ignored
  mask(cv::Rect(160, 40, 15, 40)).setTo(4);  // nobody: false positive
  const FrameScore s = scoreMask(mask, truth, kPeople);
  EXPECT_EQ(s.true_positives, 1);
  EXPECT_EQ(s.false_positives, 2);
  EXPECT_EQ(s.false_negatives, 1);  // person 2
  EXPECT_EQ(s.ignored, 1);
  EXPECT_EQ(s.detected, 3);
  EXPECT_EQ(s.scored_people, 2);
  EXPECT_FALSE(s.countsAgree());
  // Which ones (for --explain): person 2 missed; mask 2 mostly on person 2, mask 4 on nobody.
  EXPECT_EQ(s.missed_people, std::vector<std::uint32_t>{2});
  ASSERT_EQ(s.false_detections.size(), 2u);
  EXPECT_EQ(s.false_detections[0].detection, 2u);
  EXPECT_EQ(s.false_detections[0].majority, 2u);
  EXPECT_EQ(s.false_detections[1].detection, 4u);
  EXPECT_EQ(s.false_detections[1].majority, 0u);
}

TEST(ScoreMask, IouOfExactlyOneHalfMatchesAndLessDoesNot) {
  const cv::Mat truth = truthImage();
  cv::Mat mask = cv::Mat::zeros(truth.size(), CV_8UC1);
  mask(cv::Rect(10, 10, 20, 30)).setTo(1);  // half of person 1: IoU 0.5
  EXPECT_EQ(scoreMask(mask, truth, kPeople).true_positives, 1);
  mask(cv::Rect(10, 39, 20, 1)).setTo(0);   // one row less: 580 / 1200 < 0.5
  EXPECT_EQ(scoreMask(mask, truth, kPeople).true_positives, 0);
  // An oversized mask: IoU = 1200 / 2400 = 0.5 still matches; bigger does not.
  mask.setTo(0);
  mask(cv::Rect(5, 5, 30, 80)).setTo(1);
  EXPECT_EQ(scoreMask(mask, truth, kPeople).true_positives, 1);
  mask(cv::Rect(5, 85, 30, 1)).setTo(1);
  EXPECT_EQ(scoreMask(mask, truth, kPeople).true_positives, 0);
}

TEST(ScoreMask, AllFoundCountsAgreeAndAn8BitTruthWorksToo) {
  cv::Mat truth8;
  truthImage().convertTo(truth8, CV_8U);
  cv::Mat mask;
  truthImage().convertTo(mask, CV_8U);
  const FrameScore s = scoreMask(mask, truth8, kPeople);
  EXPECT_EQ(s.true_positives, 2);
  EXPECT_EQ(s.false_positives + s.false_negatives, 0);
  EXPECT_EQ(s.ignored, 1);
  EXPECT_TRUE(s.countsAgree());
}

TEST(ScoreMask, RefusesMismatchedImages) {
  EXPECT_NE(test_support::errorOf([] { scoreMask(cv::Mat::zeros(10, 10, CV_8UC1), cv::Mat::zeros(10, 12, CV_16UC1), {}); })
                .find("differ in size"),
            std::string::npos);
  EXPECT_NE(test_support::errorOf([] { scoreMask(cv::Mat::zeros(10, 10, CV_16UC1), cv::Mat::zeros(10, 10, CV_16UC1), {}); })
                .find("CV_8UC1"),
            std::string::npos);
}

TEST(ScoreClusters, PurityOfEightyPercentAndOneClusterPerPerson) {
  std::vector<std::uint32_t> labels, truth;
  auto add = [&](std::uint32_t label, std::uint32_t id, int n) {
    labels.insert(labels.end(), n, label);
    truth.insert(truth.end(), n, id);
  };
  add(1, 1, 45);  // cluster 1: 90 % person 1 -> true positive
  add(1, 0, 5);
  add(2, 2, 28);  // cluster 2: 70 % person 2 (merged with a bush) -> false positive
  add(2, 0, 12);
  add(3, 3, 30);  // cluster 3: person 3, not scored -> ignored
  add(4, 0, 20);  // cluster 4: a bush -> false positive
  add(5, 1, 17);  // cluster 5: 85 % person 1 again, less pure -> false positive (duplicate)
  add(5, 0, 3);
  const FrameScore s = scoreClusters(labels, truth, kPeople);
  EXPECT_EQ(s.true_positives, 1);
  EXPECT_EQ(s.false_positives, 3);
  EXPECT_EQ(s.false_negatives, 1);
  EXPECT_EQ(s.ignored, 1);
  EXPECT_EQ(s.missed_people, std::vector<std::uint32_t>{2});
  ASSERT_EQ(s.false_detections.size(), 3u);  // clusters 2, 4, 5: mostly person 2, a bush, person 1
  EXPECT_EQ(s.false_detections[0].majority, 2u);
  EXPECT_EQ(s.false_detections[1].majority, 0u);
  EXPECT_EQ(s.false_detections[2].majority, 1u);
  // Exactly 80 % is a match.
  EXPECT_EQ(scoreClusters({7, 7, 7, 7, 7}, {2, 2, 2, 2, 0}, kPeople).true_positives, 1);
  EXPECT_EQ(scoreClusters({7, 7, 7, 7, 7, 7}, {2, 2, 2, 2, 0, 0}, kPeople).true_positives, 0);
  EXPECT_NE(test_support::errorOf([] { scoreClusters({1, 2}, {1}, {}); }).find("2 labels but 1 truth ids"),
            std::string::npos);
}

TEST(DetectionScore, RecallPrecisionAndCountAgreementOverFrames) {
  DetectionScore total;
  EXPECT_DOUBLE_EQ(total.recall(), 1.0);
  EXPECT_DOUBLE_EQ(total.precision(), 1.0);
  EXPECT_DOUBLE_EQ(total.countAgreement(), 1.0);
  FrameScore a;  // 2 of 2 found, nothing false
  a.true_positives = 2;
  a.detected = 2;
  a.scored_people = 2;
  FrameScore b;  // 1 of 2 found, 1 false: counts agree (2 = 2) although wrong
  b.true_positives = 1;
  b.false_positives = 1;
  b.false_negatives = 1;
  b.detected = 2;
  b.scored_people = 2;
  FrameScore c;  // nobody there, one false
  c.false_positives = 1;
  c.detected = 1;
  total.add(a);
  total.add(b);
  total.add(c);
  EXPECT_DOUBLE_EQ(total.recall(), 3.0 / 4.0);
  EXPECT_DOUBLE_EQ(total.precision(), 3.0 / 5.0);
  EXPECT_DOUBLE_EQ(total.countAgreement(), 2.0 / 3.0);
  DetectionScore twice = total;
  twice.add(total);
  EXPECT_EQ(twice.frames, 6);
  EXPECT_DOUBLE_EQ(twice.recall(), total.recall());
}

TEST(WhollyInView, APersonTouchingTheBorderIsNot) {
  cv::Mat ids = cv::Mat::zeros(50, 80, CV_16UC1);
  ids(cv::Rect(10, 10, 5, 20)).setTo(4);
  ids(cv::Rect(0, 20, 5, 20)).setTo(5);   // cut by the left edge
  ids(cv::Rect(60, 30, 5, 20)).setTo(6);  // reaches the bottom row
  EXPECT_TRUE(detection::whollyInView(ids, 4));
  EXPECT_FALSE(detection::whollyInView(ids, 5));
  EXPECT_FALSE(detection::whollyInView(ids, 6));
  EXPECT_FALSE(detection::whollyInView(ids, 7));  // not in the image at all
}

}  // namespace
}  // namespace thermal_lidar_calibration
