// The order pick poses its candidates in (host/pick/candidate_order.h) and the rule that
// lets it answer before posing the rest (host/pick/pick_acceptance.h), on hand-made depth
// maps: a bin floor at 1000 mm with boxes of parts on it.
#include <gtest/gtest.h>

#include <limits>

#include "host/pick/candidate_order.h"
#include "host/pick/pick_acceptance.h"

using namespace flexsight;

namespace {

constexpr double kFloor = 1000.0;

cv::Mat floor_depth() { return cv::Mat(200, 300, CV_32FC1, cv::Scalar(kFloor)); }

OrderedCandidate candidate(int lead, const cv::Rect& box, const CandidateCues& cues) {
  OrderedCandidate c;
  c.proposals = {lead};
  c.box = box;
  c.cues = cues;
  return c;
}

TEST(CandidateGroups, OverlappingBoxesAreOnePartInTheirLeadsOrder) {
  const std::vector<cv::Rect> boxes = {{0, 0, 40, 40}, {100, 100, 40, 40}, {2, 2, 40, 40}, {200, 0, 10, 10},
                                       {101, 99, 40, 40}};
  const std::vector<std::vector<int>> groups = group_overlapping_boxes(boxes, 0.5);
  ASSERT_EQ(groups.size(), 3u);
  EXPECT_EQ(groups[0], (std::vector<int>{0, 2}));
  EXPECT_EQ(groups[1], (std::vector<int>{1, 4}));
  EXPECT_EQ(groups[2], (std::vector<int>{3}));
  // Touching boxes are two parts.
  EXPECT_EQ(group_overlapping_boxes({{0, 0, 10, 10}, {10, 0, 10, 10}}, 0.5).size(), 2u);
}

TEST(CandidateCues, AFreePartOnTopIsHighFreeAndSeenWhole) {
  cv::Mat depth = floor_depth();
  const cv::Rect box(100, 60, 40, 40);
  depth(box).setTo(950);  // a part 50 mm high, floor all around
  const CandidateCues cues = depth_cues(depth, box, kFloor);
  EXPECT_DOUBLE_EQ(cues.height_mm, 50.0);
  EXPECT_DOUBLE_EQ(cues.free_space, 1.0);
  EXPECT_DOUBLE_EQ(cues.visible_estimate, 1.0);
}

TEST(CandidateCues, APartUnderOthersIsLowBoxedInAndPartlyHidden) {
  cv::Mat depth = floor_depth();
  const cv::Rect box(100, 60, 40, 40);
  depth(box).setTo(980);  // 20 mm high
  // A part 80 mm high over its right fifth (outside the box's central half) and beside it.
  depth(cv::Rect(132, 40, 40, 80)).setTo(920);
  const CandidateCues cues = depth_cues(depth, box, kFloor);
  EXPECT_DOUBLE_EQ(cues.height_mm, 20.0);
  EXPECT_LT(cues.free_space, 0.8);
  EXPECT_GT(cues.free_space, 0.2);
  EXPECT_DOUBLE_EQ(cues.visible_estimate, 32.0 / 40.0);  // the covered columns are nearer
}

TEST(CandidateCues, NoMeasuredDepthGivesNoHeightAndNoVisibility) {
  cv::Mat depth = floor_depth();
  const cv::Rect box(100, 60, 40, 40);
  depth(box).setTo(0);
  depth.at<float>(70, 110) = std::numeric_limits<float>::quiet_NaN();
  const CandidateCues cues = depth_cues(depth, box, kFloor);
  EXPECT_EQ(cues.height_mm, 0.0);
  EXPECT_EQ(cues.visible_estimate, 0.0);
  // A box half outside the image is cut to it.
  const CandidateCues edge = depth_cues(floor_depth(), cv::Rect(280, 180, 40, 40), 990.0);
  EXPECT_EQ(edge.height_mm, 0.0);  // the floor is measured below the assumed floor depth
  EXPECT_DOUBLE_EQ(edge.visible_estimate, 1.0);
}

TEST(CandidateOrder, TheHighFreePartComesBeforeTheCoveredOneWhateverTheirDetectionOrder) {
  CandidateCues covered;
  covered.height_mm = 20.0;
  covered.free_space = 0.3;
  covered.visible_estimate = 0.6;
  covered.detection_score = 0.9;
  CandidateCues free = covered;
  free.height_mm = 60.0;
  free.free_space = 1.0;
  free.visible_estimate = 1.0;
  free.detection_score = 0.5;
  std::vector<OrderedCandidate> candidates = {candidate(0, {0, 0, 10, 10}, covered), candidate(1, {50, 0, 10, 10}, free)};
  order_candidates(candidates);
  EXPECT_EQ(candidates[0].proposals.front(), 1);
  EXPECT_GT(candidates[0].cheap_score, candidates[1].cheap_score);
  // The heights count relative to the highest of the bin: the free part's is 1.
  const CandidateOrderWeights w;
  EXPECT_DOUBLE_EQ(candidates[0].cheap_score, w.height + w.free_space + w.visible + w.detection * 0.5);
  // Weights that count only the detector give the detector's order.
  CandidateOrderWeights detector_only{0.0, 0.0, 0.0, 1.0, 0.0};
  order_candidates(candidates, detector_only);
  EXPECT_EQ(candidates[0].proposals.front(), 0);
}

TEST(CandidateOrder, TiesKeepTheProposalOrder) {
  CandidateCues same;
  same.height_mm = 10.0;
  std::vector<OrderedCandidate> candidates = {candidate(3, {0, 0, 5, 5}, same), candidate(1, {9, 0, 5, 5}, same),
                                              candidate(2, {18, 0, 5, 5}, same)};
  order_candidates(candidates);
  EXPECT_EQ(candidates[0].proposals.front(), 1);
  EXPECT_EQ(candidates[1].proposals.front(), 2);
  EXPECT_EQ(candidates[2].proposals.front(), 3);
  // A namer's score counts only where there is one (-1: none).
  CandidateCues named = same;
  named.naming_score = 0.8;
  candidates.push_back(candidate(4, {27, 0, 5, 5}, named));
  order_candidates(candidates);
  EXPECT_EQ(candidates[0].proposals.front(), 4);
}

PickCandidate posed(double pose_score, double depth_fit, double visible) {
  PickCandidate c;
  c.pose_score = pose_score;
  c.depth_fit = depth_fit;
  c.visible_fraction = visible;
  return c;
}

TEST(PickAcceptance, AGoodFitSeenWholeIsAcceptedAndEachShortfallIsNamed) {
  const AcceptanceRule rule;
  EXPECT_EQ(acceptance_failure(posed(0.8, 0.9, 0.98), rule), "");
  EXPECT_EQ(acceptance_failure(posed(rule.min_pose_score, rule.min_depth_fit, rule.min_visible_fraction), rule), "")
      << "the bounds themselves pass";
  EXPECT_EQ(acceptance_failure(posed(0.41, 0.9, 0.98), rule).rfind("pose_score 0.4100 <", 0), 0u);
  EXPECT_EQ(acceptance_failure(posed(0.8, 0.5, 0.98), rule).rfind("depth_fit 0.5000 <", 0), 0u);
  EXPECT_EQ(acceptance_failure(posed(0.8, 0.9, 0.5), rule).rfind("visible_fraction 0.5000 <", 0), 0u);
  EXPECT_NE(acceptance_failure(posed(std::numeric_limits<double>::quiet_NaN(), 0.9, 0.98), rule), "");
  // A looser rule takes what the default refuses.
  AcceptanceRule loose{0.3, 0.3, 0.3};
  EXPECT_EQ(acceptance_failure(posed(0.41, 0.5, 0.5), loose), "");
}

}  // namespace
