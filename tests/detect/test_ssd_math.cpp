// The shared maths of kernels/detect/ssd_math.h: exp and sigmoid against the C library
// in double, softmax, box decoding against a box worked out by hand, IoU.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "kernels/detect/ssd_math.h"

namespace flexsight {
namespace {

float float_from_bits(std::uint32_t bits) {
  float value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

std::uint32_t bits_of(float value) {
  std::uint32_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  return bits;
}

// |got - exact| in units of the float spacing at the exact value.
double ulps(float got, double exact) {
  const float rounded = static_cast<float>(exact);
  const double spacing =
      static_cast<double>(std::nextafter(rounded, std::numeric_limits<float>::infinity())) -
      rounded;
  return std::fabs(got - exact) / spacing;
}

// Every 61st float from `low` (negative) up to `high` (positive): about 37 million
// values over [-87, 88], every binade sampled densely.
template <class Check>
void sweep_floats(float low, float high, Check check) {
  for (std::uint32_t bits = bits_of(-0.0f); bits <= bits_of(low); bits += 61) {
    check(float_from_bits(bits));
  }
  for (std::uint32_t bits = 0; bits <= bits_of(high); bits += 61) check(float_from_bits(bits));
}

TEST(SsdMath, ExpIsWithinOneUlpOfTheLibraryOverTheRangeItReturnsNormals) {
  double worst_ulps = 0.0;
  double worst_relative = 0.0;
  float worst_at = 0.0f;
  sweep_floats(-87.0f, 88.0f, [&](float x) {
    const double exact = std::exp(static_cast<double>(x));
    const float got = ssd_exp(x);
    const double error = ulps(got, exact);
    if (error > worst_ulps) {
      worst_ulps = error;
      worst_at = x;
    }
    worst_relative = std::max(worst_relative, std::fabs(got - exact) / exact);
  });
  // Measured: 0.99 ulp, relative 8.2e-8 (every float of the range, once, off-line).
  EXPECT_LE(worst_ulps, 1.0) << "at x = " << worst_at;
  EXPECT_LT(worst_relative, 1.0e-7);
}

TEST(SsdMath, ExpEdges) {
  EXPECT_EQ(ssd_exp(0.0f), 1.0f);
  EXPECT_EQ(ssd_exp(-0.0f), 1.0f);
  EXPECT_EQ(ssd_exp(-87.01f), 0.0f) << "below the normal range: 0, on every device";
  EXPECT_EQ(ssd_exp(-1000.0f), 0.0f);
  EXPECT_GT(ssd_exp(-87.0f), std::numeric_limits<float>::min()) << "still normal at -87";
  EXPECT_TRUE(std::isfinite(ssd_exp(88.7f)));
  EXPECT_NEAR(ssd_exp(88.7f) / std::exp(static_cast<double>(88.7f)), 1.0, 1.2e-7);
  EXPECT_EQ(ssd_exp(88.8f), std::numeric_limits<float>::infinity());
  EXPECT_EQ(ssd_exp(1e30f), std::numeric_limits<float>::infinity());
  EXPECT_EQ(ssd_exp(std::numeric_limits<float>::infinity()),
            std::numeric_limits<float>::infinity());
  EXPECT_EQ(ssd_exp(-std::numeric_limits<float>::infinity()), 0.0f);
  EXPECT_TRUE(std::isnan(ssd_exp(std::numeric_limits<float>::quiet_NaN())));
}

TEST(SsdMath, SigmoidIsWithinThreeUlpsOfTheLibrary) {
  double worst_ulps = 0.0;
  double worst_relative = 0.0;
  sweep_floats(-30.0f, 30.0f, [&](float x) {
    const double exact = 1.0 / (1.0 + std::exp(-static_cast<double>(x)));
    const float got = ssd_sigmoid(x);
    worst_ulps = std::max(worst_ulps, ulps(got, exact));
    worst_relative = std::max(worst_relative, std::fabs(got - exact) / exact);
  });
  // Measured: 2.5 ulps, relative 1.5e-7 (three roundings on top of exp's error).
  EXPECT_LE(worst_ulps, 3.0);
  EXPECT_LT(worst_relative, 2.0e-7);
  EXPECT_EQ(ssd_sigmoid(0.0f), 0.5f);
  EXPECT_EQ(ssd_sigmoid(-100.0f), 0.0f);
  EXPECT_EQ(ssd_sigmoid(100.0f), 1.0f);
  EXPECT_EQ(ssd_sigmoid(std::numeric_limits<float>::infinity()), 1.0f);
}

TEST(SsdMath, SoftmaxMatchesTheLibraryAndSumsToOne) {
  const std::vector<float> row = {2.0f, -1.0f, 0.5f, 3.25f, -7.0f, 0.0f};  // background first
  const int classes = static_cast<int>(row.size()) - 1;
  EXPECT_EQ(ssd_row_max(row.data(), classes + 1), 3.25f);
  // Written with a stride, as into the class-major scores.
  std::vector<float> scores(3 * classes, -1.0f);
  ssd_softmax_scores(row.data(), classes, scores.data(), 3);
  double exact_sum = 0.0;
  for (float l : row) exact_sum += std::exp(static_cast<double>(l));
  double total = std::exp(static_cast<double>(row[0])) / exact_sum;  // the background's share
  for (int c = 0; c < classes; ++c) {
    const float p = scores[3 * c];
    EXPECT_NEAR(p, std::exp(static_cast<double>(row[c + 1])) / exact_sum, 2e-7) << "class " << c;
    EXPECT_EQ(scores[3 * c + 1], -1.0f) << "written only at the stride";
    total += p;
  }
  EXPECT_NEAR(total, 1.0, 1e-6);
}

TEST(SsdMath, SigmoidScoreIsTheSigmoidOfTheClassLogit) {
  EXPECT_EQ(ssd_sigmoid_score(0.0f), 0.5f);
  EXPECT_EQ(ssd_sigmoid_score(-2.0f), ssd_sigmoid(-2.0f));
}

TEST(SsdMath, NanScoresAreZeroAndClippedZerosArePositive) {
  // NaN's sign and payload differ between compilers; -0 and +0 differ in their bytes.
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(bits_of(ssd_sigmoid_score(nan)), 0u);
  const std::vector<float> row = {0.0f, nan, 1.0f};
  float scores[2] = {-1.0f, -1.0f};
  ssd_softmax_scores(row.data(), 2, scores, 1);
  EXPECT_EQ(bits_of(scores[1]), 0u)
      << "a NaN anywhere in the row spoils the softmax: no detection from it";
  EXPECT_EQ(bits_of(ssd_clip_unit(-0.0f)), 0u);
  EXPECT_EQ(bits_of(ssd_clip_unit(nan)), 0u);
  EXPECT_EQ(ssd_clip_unit(-0.5f), 0.0f);
  EXPECT_EQ(ssd_clip_unit(0.25f), 0.25f);
  EXPECT_EQ(ssd_clip_unit(std::numeric_limits<float>::infinity()), 1.0f);
}

TEST(SsdMath, DecodeGivesTheBoxWorkedOutByHand) {
  // Anchor centre (y 0.5, x 0.4), size (h 0.2, w 0.3). Encoding ty = 1 -> 0.1 anchor
  // heights down: y 0.52; tx = -2 -> 0.2 anchor widths left: x 0.34; th = 5 ln 2 ->
  // height doubled: 0.4; tw = 0 -> width 0.3. Corners: x 0.19..0.49, y 0.32..0.72.
  const float anchor[4] = {0.5f, 0.4f, 0.2f, 0.3f};
  const float encoding[4] = {1.0f, -2.0f, 5.0f * 0.693147181f, 0.0f};
  const SsdBox box = ssd_decode_box(encoding, anchor, 10.0f, 10.0f, 5.0f, 5.0f);
  EXPECT_NEAR(box.x_min, 0.19f, 1e-6f);
  EXPECT_NEAR(box.y_min, 0.32f, 1e-6f);
  EXPECT_NEAR(box.x_max, 0.49f, 1e-6f);
  EXPECT_NEAR(box.y_max, 0.72f, 1e-6f);
}

TEST(SsdMath, DecodeClipsToTheImage) {
  // A box of twice the image's size centred on its top-left corner spans [-1, 1] in x
  // and y: clipped to [0, 1].
  const float anchor[4] = {0.0f, 0.0f, 1.0f, 1.0f};
  const float encoding[4] = {0.0f, 0.0f, 5.0f * 0.693147181f, 5.0f * 0.693147181f};
  const SsdBox box = ssd_decode_box(encoding, anchor, 10.0f, 10.0f, 5.0f, 5.0f);
  EXPECT_EQ(box.x_min, 0.0f);
  EXPECT_EQ(box.y_min, 0.0f);
  EXPECT_EQ(box.x_max, 1.0f);
  EXPECT_EQ(box.y_max, 1.0f);
  // A NaN encoding gives an empty box at the origin, which overlaps nothing.
  const float nan_encoding[4] = {std::numeric_limits<float>::quiet_NaN(), 0.0f, 0.0f, 0.0f};
  const SsdBox nan_box = ssd_decode_box(nan_encoding, anchor, 10.0f, 10.0f, 5.0f, 5.0f);
  EXPECT_EQ(nan_box.y_min, 0.0f);
  EXPECT_EQ(nan_box.y_max, 0.0f);
  EXPECT_EQ(ssd_iou(nan_box, nan_box), 0.0f);
}

SsdBox box(float x_min, float y_min, float x_max, float y_max) {
  return {x_min, y_min, x_max, y_max};
}

TEST(SsdMath, IouOfKnownPairs) {
  // Overlap 0.2 x 0.2 = 0.04 of two 0.16 boxes: 0.04 / 0.28 = 1/7.
  EXPECT_NEAR(ssd_iou(box(0.0f, 0.0f, 0.4f, 0.4f), box(0.2f, 0.2f, 0.6f, 0.6f)), 1.0 / 7.0, 1e-7);
  // One inside the other: 0.04 / 0.16.
  EXPECT_NEAR(ssd_iou(box(0.0f, 0.0f, 0.4f, 0.4f), box(0.1f, 0.1f, 0.3f, 0.3f)), 0.25, 1e-7);
  EXPECT_EQ(ssd_iou(box(0.1f, 0.2f, 0.3f, 0.7f), box(0.1f, 0.2f, 0.3f, 0.7f)), 1.0f);
  EXPECT_EQ(ssd_iou(box(0.0f, 0.0f, 0.2f, 0.2f), box(0.2f, 0.0f, 0.4f, 0.2f)), 0.0f)
      << "touching";
  EXPECT_EQ(ssd_iou(box(0.0f, 0.0f, 0.2f, 0.2f), box(0.5f, 0.5f, 0.6f, 0.6f)), 0.0f);
  EXPECT_EQ(ssd_iou(box(0.0f, 0.0f, 0.4f, 0.4f), box(0.2f, 0.2f, 0.6f, 0.6f)),
            ssd_iou(box(0.2f, 0.2f, 0.6f, 0.6f), box(0.0f, 0.0f, 0.4f, 0.4f)))
      << "symmetric";
}

TEST(SsdMath, OrdersAreStrictAndTotal) {
  EXPECT_TRUE(ssd_candidate_before(0.9f, 5, 0.8f, 1));
  EXPECT_TRUE(ssd_candidate_before(0.8f, 1, 0.8f, 5)) << "equal scores: lower anchor first";
  EXPECT_FALSE(ssd_candidate_before(0.8f, 5, 0.8f, 5));
  EXPECT_TRUE(ssd_detection_before(0.8f, 0, 9, 0.8f, 1, 2)) << "then lower class";
  EXPECT_TRUE(ssd_detection_before(0.8f, 1, 2, 0.8f, 1, 9)) << "then lower anchor";
  EXPECT_FALSE(ssd_detection_before(0.8f, 1, 2, 0.8f, 1, 2));
}

}  // namespace
}  // namespace flexsight
