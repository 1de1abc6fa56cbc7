// Post-processing stages: left/right check, background filling, weighted median.
#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <random>
#include <string>

#include "fallback/stereo/postprocess_reference.h"
#include "fallback/stereo/weight_table.h"
#include "kernels/stereo/postprocess_math.h"
#include "tests/common/test_support.h"

using namespace flexsight;

TEST(LeftRightCheck, AcceptsAgreementAndRejectsOcclusionAndOutside) {
  // One row of 6 pixels. Left disparity 2 everywhere but pixel 4 (d = 0.4); the right
  // view says 2 everywhere but right pixel 1 (d = 5).
  std::vector<float> left = {2, 2, 2, 2, 0.4f, 2};
  std::vector<float> right = {2, 5, 2, 2, 2, 2};
  auto ok = left_right_check(left, right, 6, 1, PMS_VIEW_LEFT, 1.0f, 1);
  // x=0,1: match x - 2 < 0 -> outside; x=2: right[0]=2 ok; x=3: right[1]=5 bad;
  // x=4: round(3.6)=4, |0.4-2| > 1 bad; x=5: right[3]=2 ok.
  EXPECT_EQ(ok, (std::vector<std::uint8_t>{0, 0, 1, 0, 0, 1}));
}

TEST(LeftRightCheck, TheRightViewLooksToTheRight) {
  // The same row seen from the right view: right pixel x matches left pixel x + d.
  std::vector<float> right = {2, 5, 2, 2, 2, 2};
  std::vector<float> left = {2, 2, 2, 2, 0.4f, 2};
  auto ok = left_right_check(right, left, 6, 1, PMS_VIEW_RIGHT, 1.0f, 1);
  // x=0: left[2]=2 ok; x=1: x+5=6 outside; x=2: left[4]=0.4 bad; x=3: left[5]=2 ok;
  // x=4,5: x+2 outside.
  EXPECT_EQ(ok, (std::vector<std::uint8_t>{1, 0, 0, 1, 0, 0}));
}

TEST(FillInconsistent, TakesTheLowerOfTheNearestValidPlanes) {
  // Row of 5: valid pixels 0 (plane d = 10) and 4 (plane d = 3 + 0.5 x); pixel 2
  // between them takes d = min(10, 4) -> the right one; pixel 1 likewise.
  std::vector<float> planes(4 * 5, 0.0f);
  planes[2] = 10.0f;
  planes[4 * 4 + 0] = 0.5f;
  planes[4 * 4 + 2] = 3.0f;
  std::vector<std::uint8_t> ok = {1, 0, 0, 0, 1};
  auto filled = fill_inconsistent(planes, ok, 5, 1, INFINITY, 1);
  for (int x = 1; x <= 3; ++x) {
    EXPECT_EQ(filled[4 * x], 0.5f) << x;
    EXPECT_EQ(filled[4 * x + 2], 3.0f) << x;
  }
  EXPECT_EQ(filled[2], 10.0f);  // valid pixels keep their plane
}

TEST(FillInconsistent, UsesTheOnlySideThereIsOrKeepsItsOwn) {
  std::vector<float> planes = {0, 0, 7, 0, 0, 0, 8, 0, 0, 0, 9, 0};
  auto one_side = fill_inconsistent(planes, {0, 0, 1}, 3, 1, INFINITY, 1);
  EXPECT_EQ(one_side[2], 9.0f);
  EXPECT_EQ(one_side[6], 9.0f);
  auto none = fill_inconsistent(planes, {0, 0, 0}, 3, 1, 2.0f, 1);
  EXPECT_EQ(none, planes);
}

TEST(FillInconsistent, KeepsTheFilledDisparityNearItsSource) {
  // Row of 12: valid pixel 0 with the plane d = 20 - 1.5 x (a steep slope), valid pixel
  // 11 with d = 30. Plain extrapolation gives pixel x the disparity 20 - 1.5 x; limited
  // to 2 px it stays within [18, 22] of the source's 20, the plane keeping its slope.
  std::vector<float> planes(4 * 12, 0.0f);
  planes[0] = -1.5f;
  planes[2] = 20.0f;
  planes[4 * 11 + 2] = 30.0f;
  std::vector<std::uint8_t> ok(12, 0);
  ok[0] = ok[11] = 1;
  const auto plain = fill_inconsistent(planes, ok, 12, 1, INFINITY, 1);
  const auto limited = fill_inconsistent(planes, ok, 12, 1, 2.0f, 1);
  for (int x = 1; x <= 10; ++x) {
    const float* p = &plain[4 * x];
    const float* l = &limited[4 * x];
    EXPECT_EQ(p[0], -1.5f) << x;
    EXPECT_EQ(p[2], 20.0f) << x;  // copied as it is
    EXPECT_EQ(l[0], -1.5f) << x;  // slope kept
    const float d = l[0] * static_cast<float>(x) + l[2];
    EXPECT_FLOAT_EQ(d, std::max(20.0f - 1.5f * static_cast<float>(x), 18.0f)) << x;
  }
  // A limit of 0 fills with the source's own disparity (fronto-parallel in effect).
  const auto constant = fill_inconsistent(planes, ok, 12, 1, 0.0f, 1);
  EXPECT_FLOAT_EQ(-1.5f * 10.0f + constant[4 * 10 + 2], 20.0f);
}

TEST(WeightedMedian, MatchesTheDefinitionOnRandomSamples) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> value(0, 50), weight(0, 1);
  for (int round = 0; round < 200; ++round) {
    int n = 1 + round % 40;
    std::vector<float> values(n), weights(n);
    for (int i = 0; i < n; ++i) {
      values[i] = std::floor(value(rng) * 4) / 4;  // ties on purpose
      weights[i] = weight(rng);
    }
    std::vector<float> sorted = values;
    std::sort(sorted.begin(), sorted.end());
    float got = pms_weighted_median(values.data(), weights.data(), sorted.data(), n);
    // Definition: smallest sample value whose cumulative weight reaches half the total.
    double total = 0;
    for (float w : weights) total += w;
    float expected = sorted.back();
    for (float v : sorted) {
      double below = 0;
      for (int i = 0; i < n; ++i)
        if (values[i] <= v) below += weights[i];
      if (below >= total / 2 - 1e-6) {
        expected = v;
        break;
      }
    }
    EXPECT_EQ(got, expected) << "round " << round;
  }
}

// A background margin that lets every consistent pixel vote.
constexpr float kEveryVote = FLT_MAX;

TEST(WeightedMedian, FilterTouchesOnlyInconsistentPixels) {
  const int w = 9, h = 7;
  ViewImage image = make_view_image(cv::Mat(h, w, CV_8UC3, cv::Scalar(50, 50, 50)));
  std::vector<float> disparity(w * h, 4.0f);
  disparity[3 * w + 4] = 30.0f;  // an outlier, inconsistent
  disparity[0] = 31.0f;          // an outlier, but consistent: kept
  std::vector<std::uint8_t> ok(w * h, 1);
  ok[3 * w + 4] = 0;
  auto weights = make_support_weight_table(10.0f);
  auto out = weighted_median_filled(disparity, ok, image, weights.data(), 2, 1, kEveryVote, 1);
  EXPECT_EQ(out[3 * w + 4], 4.0f);
  EXPECT_EQ(out[0], 31.0f);
}

TEST(WeightedMedian, OnlyConsistentPixelsVoteForAFilledPixel) {
  // A 5x5 window around the centre: 20 inconsistent pixels say 30, the 5 consistent
  // ones (the top row) say 4. Counting every vote the median would be 30.
  const int w = 5, h = 5;
  ViewImage image = make_view_image(cv::Mat(h, w, CV_8UC3, cv::Scalar(50, 50, 50)));
  std::vector<float> disparity(w * h, 30.0f);
  std::vector<std::uint8_t> ok(w * h, 0);
  for (int x = 0; x < w; ++x) {
    disparity[x] = 4.0f;
    ok[x] = 1;
  }
  auto weights = make_support_weight_table(10.0f);
  auto out = weighted_median_filled(disparity, ok, image, weights.data(), 2, 1, kEveryVote, 1);
  EXPECT_EQ(out[2 * w + 2], 4.0f);
  // The bottom-right corner's 3x3 window (radius 1) holds no consistent pixel: it keeps
  // its filled value.
  auto small = weighted_median_filled(disparity, ok, image, weights.data(), 1, 1, kEveryVote, 1);
  EXPECT_EQ(small[4 * w + 4], 30.0f);
  EXPECT_EQ(small[1 * w + 1], 4.0f);  // its window reaches the top row: 3 votes of 4 ...
  // ... against 6 of 30 would lose if the inconsistent pixels voted.
  EXPECT_EQ(weighted_median_all(disparity, image, weights.data(), 1, 1)[1 * w + 1], 30.0f);
}

TEST(WeightedMedian, VotesInFrontOfTheFilledBackgroundAreLeftOut) {
  // A hole (the middle column, filled with the background's 10) between a consistent
  // foreground (left, 25, the hole's colour) and background (right, 10.5 and 11, colours
  // further away), so that in the 5x5 window the foreground's votes outweigh the
  // background's, and 10.5 outweighs 11.
  const int w = 5, h = 5;
  cv::Mat colour(h, w, CV_8UC3, cv::Scalar(50, 50, 50));
  colour.col(3).setTo(cv::Scalar(55, 55, 55));
  colour.col(4).setTo(cv::Scalar(60, 60, 60));
  ViewImage image = make_view_image(colour);
  std::vector<float> disparity(w * h);
  std::vector<std::uint8_t> ok(w * h, 1);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      disparity[y * w + x] = x < 2 ? 25.0f : (x == 2 ? 10.0f : (x == 3 ? 10.5f : 11.0f));
    }
    ok[y * w + 2] = 0;
  }
  auto weights = make_support_weight_table(10.0f);
  const int centre = 2 * w + 2;
  EXPECT_EQ(weighted_median_filled(disparity, ok, image, weights.data(), 2, 1, kEveryVote, 1)[centre],
            25.0f);
  // Margin 2: 25 > 10 + 2 does not vote; the background's median is 10.5.
  EXPECT_EQ(weighted_median_filled(disparity, ok, image, weights.data(), 2, 1, 2.0f, 1)[centre],
            10.5f);
  // Margin 0.25: no vote is left (10.5 > 10.25): the pixel keeps its filled value.
  EXPECT_EQ(weighted_median_filled(disparity, ok, image, weights.data(), 2, 1, 0.25f, 1)[centre],
            10.0f);
}

TEST(WeightedMedian, FilterOverAllPixelsRemovesAnIsolatedOutlierAndKeepsAnEdge) {
  // Left half dark at disparity 10, right half bright at disparity 20, one consistent
  // outlier (40) inside the left half.
  const int w = 12, h = 9;
  cv::Mat rgb(h, w, CV_8UC3, cv::Scalar(40, 40, 40));
  rgb(cv::Rect(6, 0, 6, h)).setTo(cv::Scalar(200, 200, 200));
  ViewImage image = make_view_image(rgb);
  std::vector<float> disparity(w * h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) disparity[y * w + x] = x < 6 ? 10.0f : 20.0f;
  }
  disparity[4 * w + 3] = 40.0f;
  auto weights = make_support_weight_table(40.0f);
  auto out = weighted_median_all(disparity, image, weights.data(), 3, 1);
  EXPECT_EQ(out[4 * w + 3], 10.0f);
  // Next to the edge the window is half across it; the colour weights keep each side.
  for (int y = 0; y < h; ++y) {
    EXPECT_EQ(out[y * w + 5], 10.0f) << "row " << y;
    EXPECT_EQ(out[y * w + 6], 20.0f) << "row " << y;
  }
  // Radius 0 is the identity.
  EXPECT_EQ(weighted_median_all(disparity, image, weights.data(), 0, 1), disparity);
}

TEST(Confidence, IsOneOverOnePlusDisagreement) {
  std::vector<float> left = {0, 0, 3, 3};
  std::vector<float> right = {1, 0, 0, 0};
  // x=2: d=3 -> right x=-1 outside: 0; x=3: right[0]=1 -> 1/(1+2).
  EXPECT_EQ(pms_confidence(left.data(), right.data(), 4, 2, 0, -1.0f), 0.0f);
  EXPECT_FLOAT_EQ(pms_confidence(left.data(), right.data(), 4, 3, 0, -1.0f), 1.0f / 3.0f);
  EXPECT_EQ(pms_confidence(left.data(), right.data(), 4, 1, 0, -1.0f), 1.0f);
}

// A map from rows of text: '.' is disparity 0, a digit k is disparity 10 + k.
static std::vector<float> map_from_rows(const std::vector<std::string>& rows) {
  std::vector<float> d;
  for (const auto& row : rows) {
    for (char c : row) d.push_back(c == '.' ? 0.0f : 10.0f + static_cast<float>(c - '0'));
  }
  return d;
}

TEST(LargeSegmentMask, MarksOnlySegmentsBelowTheSize) {
  // A 3-pixel island (an L, 4-connected) and a single pixel in a background of 0.
  const std::vector<float> d = map_from_rows({"......",
                                              ".00...",
                                              ".0....",
                                              "....0.",
                                              "......"});
  const auto mask = large_segment_mask(d, 6, 5, 1.0f, 4);
  for (size_t i = 0; i < d.size(); ++i) {
    EXPECT_EQ(mask[i], d[i] == 0.0f ? 1 : 0) << "pixel " << i;
  }
  // Size 3: the L is kept, the single pixel is not; size 1 and 0 keep everything.
  const auto three = large_segment_mask(d, 6, 5, 1.0f, 3);
  EXPECT_EQ(three[1 * 6 + 1], 1);
  EXPECT_EQ(three[3 * 6 + 4], 0);
  EXPECT_EQ(large_segment_mask(d, 6, 5, 1.0f, 1), std::vector<std::uint8_t>(d.size(), 1));
  EXPECT_EQ(large_segment_mask(d, 6, 5, 1.0f, 0), std::vector<std::uint8_t>(d.size(), 1));
}

TEST(LargeSegmentMask, JoinsFourNeighboursWithinTheStepOnly) {
  // Two pixels that touch only diagonally are two segments of one pixel each.
  const std::vector<float> diagonal = map_from_rows({"0..", ".0.", "..."});
  const auto mask = large_segment_mask(diagonal, 3, 3, 1.0f, 2);
  EXPECT_EQ(mask[0], 0);
  EXPECT_EQ(mask[4], 0);
  EXPECT_EQ(mask[8], 1);
  // A ramp rising 0.5 per pixel is one segment with a step of 0.5, none below it.
  std::vector<float> ramp(8);
  for (int x = 0; x < 8; ++x) ramp[x] = 0.5f * static_cast<float>(x);
  EXPECT_EQ(large_segment_mask(ramp, 8, 1, 0.5f, 8), std::vector<std::uint8_t>(8, 1));
  EXPECT_EQ(large_segment_mask(ramp, 8, 1, 0.25f, 2), std::vector<std::uint8_t>(8, 0));
}

TEST(LargeSegmentMask, FollowingSlopesKeepsASteepWallWhole) {
  // A wall rising 2 px a row: every row is its own segment under a 1-px step, and the
  // whole wall one segment when a step may continue the step beside it.
  const int w = 6, h = 8;
  std::vector<float> wall(w * h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) wall[y * w + x] = 10.0f + 2.0f * static_cast<float>(y);
  }
  EXPECT_EQ(large_segment_mask(wall, w, h, 1.0f, w + 1, false),
            std::vector<std::uint8_t>(wall.size(), 0));
  EXPECT_EQ(large_segment_mask(wall, w, h, 1.0f, w * h, true),
            std::vector<std::uint8_t>(wall.size(), 1));
  // A bend (2 px a row, then 4) is followed too: each step continues one beside it.
  std::vector<float> bend(h);
  for (int y = 0; y < h; ++y) bend[y] = y < 4 ? 2.0f * y : 6.0f + 4.0f * (y - 3);
  EXPECT_EQ(large_segment_mask(bend, 1, h, 1.0f, h, true), std::vector<std::uint8_t>(h, 1));
}

TEST(LargeSegmentMask, FollowingSlopesStillCutsOffAnIsland) {
  // A 2x2 island 5 px above a flat field and a 2x2 island 5 px above a wall rising 2 px a
  // row: its border is a jump unlike the slope on either side, so it stays apart.
  const int w = 8, h = 8;
  std::vector<float> flat(w * h, 3.0f), wall(w * h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) wall[y * w + x] = 2.0f * static_cast<float>(y);
  }
  for (int y = 3; y < 5; ++y) {
    for (int x = 3; x < 5; ++x) {
      flat[y * w + x] += 5.0f;
      wall[y * w + x] += 5.0f;
    }
  }
  for (const auto* d : {&flat, &wall}) {
    const auto kept = large_segment_mask(*d, w, h, 1.0f, 5, true);
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const bool in_island = x >= 3 && x < 5 && y >= 3 && y < 5;
        EXPECT_EQ(kept[y * w + x], in_island ? 0 : 1) << "pixel " << x << ", " << y;
      }
    }
  }
}

TEST(LargeSegmentMask, RefillGivesAnIslandTheDisparityAroundIt) {
  // The refill of the pipeline: flat planes, background filling from the kept pixels,
  // then the hole median voting the kept ones. A 2x2 island of 15 in a field of 3.
  const int w = 8, h = 6;
  std::vector<float> d(w * h, 3.0f);
  for (int y = 2; y < 4; ++y) {
    for (int x = 3; x < 5; ++x) d[y * w + x] = 15.0f;
  }
  const auto kept = large_segment_mask(d, w, h, 1.0f, 5);
  const auto planes = fill_inconsistent(flat_planes(d), kept, w, h, INFINITY, 1);
  for (int i = 0; i < w * h; ++i) {
    EXPECT_EQ(planes[4 * i + 0], 0.0f);
    EXPECT_EQ(planes[4 * i + 1], 0.0f);
    EXPECT_EQ(planes[4 * i + 2], 3.0f) << "pixel " << i;  // the island took its neighbours'
  }
  ViewImage image = make_view_image(cv::Mat(h, w, CV_8UC3, cv::Scalar(50, 50, 50)));
  auto weights = make_support_weight_table(10.0f);
  std::vector<float> filled(w * h);
  for (int i = 0; i < w * h; ++i) filled[i] = planes[4 * i + 2];
  EXPECT_EQ(weighted_median_filled(filled, kept, image, weights.data(), 2, 1, 2.0f, 1),
            std::vector<float>(w * h, 3.0f));
}

TEST(MaskAnd, ClearsWhereTheOtherIsZero) {
  std::vector<std::uint8_t> mask = {1, 1, 0, 0};
  mask_and(mask, {1, 0, 1, 0});
  EXPECT_EQ(mask, (std::vector<std::uint8_t>{1, 0, 0, 0}));
}
