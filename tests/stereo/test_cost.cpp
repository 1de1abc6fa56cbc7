// The adaptive-support-weighted matching cost against hand-computed values and against
// an independent double-precision implementation.
#include <gtest/gtest.h>

#include <algorithm>
#include <bitset>
#include <cmath>
#include <cstdint>
#include <limits>

#include "fallback/stereo/image_pyramid.h"
#include "fallback/stereo/weight_table.h"
#include "kernels/stereo/pms_math.h"
#include "tests/common/test_support.h"

using namespace flexsight;

namespace {

ViewImage grey_row(std::initializer_list<float> values) {
  cv::Mat rgb(1, static_cast<int>(values.size()), CV_8UC3);
  int x = 0;
  for (float v : values) rgb.at<cv::Vec3b>(0, x++) = cv::Vec3b(v, v, v);
  return make_view_image(rgb);
}

PmsCostParams params(int radius, int step, float tau_color, float tau_gradient,
                     float census_weight = 0.0f, float census_cap = 24.0f) {
  return {radius, radius, step, 0.9f, 1.0f - 0.9f, tau_color, tau_gradient,
          census_weight, census_cap};
}

float cost(const ViewImage& ref, const ViewImage& other, const std::vector<float>& weights,
           PmsCostParams p, int x, int y, float a, float b, float c, float direction,
           float bound = std::numeric_limits<float>::max()) {
  return pms_plane_cost(ref.color.data(), ref.gradient.data(), other.color.data(),
                        other.gradient.data(), weights.data(), ref.width, ref.height, p, x, y, a,
                        b, c, direction, bound);
}

// The 5x5 census of grey r + g + b at (x, y), written from its definition: bit k for
// the k-th neighbour in row order (centre skipped), set when darker, clamped borders.
std::uint32_t census_of(const ViewImage& v, int x, int y) {
  auto grey = [&](int qx, int qy) {
    qx = std::clamp(qx, 0, v.width - 1);
    qy = std::clamp(qy, 0, v.height - 1);
    const float* c = &v.color[4 * (qy * v.width + qx)];
    return c[0] + c[1] + c[2];
  };
  std::uint32_t bits = 0;
  int k = 0;
  for (int dy = -2; dy <= 2; ++dy) {
    for (int dx = -2; dx <= 2; ++dx) {
      if (dx == 0 && dy == 0) continue;
      if (grey(x + dx, y + dy) < grey(x, y)) bits |= 1u << k;
      ++k;
    }
  }
  return bits;
}

// Independent implementation in double precision, with explicit loops over the whole
// window and a skip for outside pixels.
double reference_cost(const ViewImage& ref, const ViewImage& other, double gamma,
                      double gamma_distance, PmsCostParams p, int px, int py, double a, double b,
                      double c, double direction) {
  double sum = 0;
  const float* centre = &ref.color[4 * (py * ref.width + px)];
  for (int dy = -p.radius; dy <= p.radius; ++dy) {
    for (int dx = -p.radius; dx <= p.radius; ++dx) {
      if (dx % p.step != 0 || dy % p.step != 0) continue;
      int qx = px + dx, qy = py + dy;
      if (qx < 0 || qy < 0 || qx >= ref.width || qy >= ref.height) continue;
      const float* q = &ref.color[4 * (qy * ref.width + qx)];
      double weight = std::exp(-(std::fabs(centre[0] - q[0]) + std::fabs(centre[1] - q[1]) +
                                 std::fabs(centre[2] - q[2])) / gamma) *
                      std::exp(-std::sqrt(static_cast<double>(dx * dx + dy * dy)) / gamma_distance);
      double mx = qx + direction * (a * qx + b * qy + c);
      mx = std::min(std::max(mx, 0.0), ref.width - 1.0);
      int x0 = static_cast<int>(std::floor(mx));
      int x1 = std::min(x0 + 1, ref.width - 1);
      double t = mx - x0;
      double color = 0, grad = 0;
      for (int ch = 0; ch < 3; ++ch) {
        double m = (1 - t) * other.color[4 * (qy * ref.width + x0) + ch] +
                   t * other.color[4 * (qy * ref.width + x1) + ch];
        color += std::fabs(q[ch] - m);
      }
      for (int ch = 0; ch < 2; ++ch) {
        double m = (1 - t) * other.gradient[2 * (qy * ref.width + x0) + ch] +
                   t * other.gradient[2 * (qy * ref.width + x1) + ch];
        grad += std::fabs(ref.gradient[2 * (qy * ref.width + qx) + ch] - m);
      }
      const int nearest = t < 0.5 ? x0 : x1;
      const double census =
          std::bitset<32>(census_of(ref, qx, qy) ^ census_of(other, nearest, qy)).count();
      sum += weight * (0.1 * std::min(color, static_cast<double>(p.tau_color)) +
                       0.9 * std::min(grad, static_cast<double>(p.tau_gradient)) +
                       p.census_weight * std::min(census, static_cast<double>(p.census_cap)));
    }
  }
  return sum;
}

}  // namespace

TEST(MatchingCost, HandComputedTruncatedCase) {
  // Left grey 10 20 40, right grey 0 30 60; plane d = 0.5 at pixel 1, window 3x1.
  // Gradients (central differences, clamped): left 5 15 10, right 15 30 15.
  // q=0: match x = -0.5 -> 0: colour 3*10 -> tau 10, gradient |5-15| -> tau 2: 2.8,
  //      weight exp(-30/10).
  // q=1: match 0.5: colour 3*|20-15| -> 10, gradient |15-22.5| -> 2: 2.8, weight 1.
  // q=2: match 1.5: colour 3*|40-45| -> 10, gradient |10-22.5| -> 2: 2.8, weight exp(-6).
  ViewImage left = grey_row({10, 20, 40});
  ViewImage right = grey_row({0, 30, 60});
  auto weights = make_support_weight_table(10.0f);
  float got = cost(left, right, weights, params(1, 1, 10.0f, 2.0f), 1, 0, 0, 0, 0.5f, -1.0f);
  EXPECT_NEAR(got, 2.8 * (std::exp(-3.0) + 1.0 + std::exp(-6.0)), 1e-5);
}

TEST(MatchingCost, HandComputedUntruncatedCase) {
  // Same pair without truncation: q=0: 0.1*30 + 0.9*10 = 12; q=1: 0.1*15 + 0.9*7.5 =
  // 8.25; q=2: 0.1*15 + 0.9*12.5 = 12.75.
  ViewImage left = grey_row({10, 20, 40});
  ViewImage right = grey_row({0, 30, 60});
  auto weights = make_support_weight_table(10.0f);
  float got = cost(left, right, weights, params(1, 1, 100.0f, 100.0f), 1, 0, 0, 0, 0.5f, -1.0f);
  EXPECT_NEAR(got, 12.0 * std::exp(-3.0) + 8.25 + 12.75 * std::exp(-6.0), 1e-4);
}

TEST(MatchingCost, ZeroForTheTrueShift) {
  // Left pixel x shows scene point x, right pixel x' shows x' + 3: with d = 3 every
  // matched pixel away from the border compares equal values.
  cv::Mat big = testing_support::random_rgb8(40, 12, 5);
  cv::Mat left_rgb = big(cv::Rect(0, 0, 30, 12)).clone();
  cv::Mat right_rgb = big(cv::Rect(3, 0, 30, 12)).clone();
  ViewImage left = make_view_image(left_rgb), right = make_view_image(right_rgb);
  auto weights = make_support_weight_table(10.0f);
  // Gradients at the image border use one-sided neighbours, so stay 2 px inside.
  EXPECT_EQ(cost(left, right, weights, params(3, 1, 10, 2), 15, 6, 0, 0, 3.0f, -1.0f), 0.0f);
  EXPECT_GT(cost(left, right, weights, params(3, 1, 10, 2), 15, 6, 0, 0, 4.0f, -1.0f), 1.0f);
  // And the right view matches at x + d.
  EXPECT_EQ(cost(right, left, weights, params(3, 1, 10, 2), 12, 6, 0, 0, 3.0f, 1.0f), 0.0f);
}

// Other neighbourhoods, on a 25x3 image whose grey rises left to right on the centre
// row and whose rows above and below are black. The centre row's census (1x25) at its
// middle pixel sees its 12 left neighbours darker: bits 0..11, whatever the other rows
// hold. A 3x3 square with a 19-px centre row counts the 3 neighbours above first (all
// darker: bits 0..2), then the row's 9 left ones (bits 3..11), its 9 right ones, and the
// 3 below (bits 21..23).
// A window of one row (radius_rows 0) sums the centre row only: rows above and below
// that match badly under the plane cost nothing, and they do in the square window.
TEST(Cost, AWindowOfOneRowSumsTheCentreRowOnly) {
  cv::Mat left(5, 12, CV_8UC3), right(5, 12, CV_8UC3);
  for (int y = 0; y < 5; ++y) {
    for (int x = 0; x < 12; ++x) {
      left.at<cv::Vec3b>(y, x) = cv::Vec3b::all(static_cast<uchar>(20 * x));
      right.at<cv::Vec3b>(y, x) = cv::Vec3b::all(static_cast<uchar>(y == 2 ? 20 * x : 7 * std::abs(y - 2)));
    }
  }
  const ViewImage l = make_view_image(left), r = make_view_image(right);
  const std::vector<float> weights = make_support_weight_table(10.0f, 20.0f);
  PmsCostParams p = params(2, 1, 10.0f, 2.0f);
  EXPECT_GT(cost(l, r, weights, p, 6, 2, 0, 0, 0.0f, -1.0f), 1.0f);
  p.radius_rows = 0;
  EXPECT_EQ(cost(l, r, weights, p, 6, 2, 0, 0, 0.0f, -1.0f), 0.0f);
}

TEST(Census, OtherShapesReadTheirNeighboursInRowOrder) {
  cv::Mat rgb8(3, 25, CV_8UC3, cv::Scalar(0, 0, 0));
  for (int x = 0; x < 25; ++x) rgb8.at<cv::Vec3b>(1, x) = cv::Vec3b::all(static_cast<uchar>(10 * x));
  const auto census_at = [&](PmsCensusShape shape, int x) {
    const ViewImage v = make_view_image(rgb8, shape);
    return static_cast<std::uint32_t>(v.color[4 * (25 + x) + 3]);
  };
  EXPECT_EQ(census_at({0, 12, 12}, 12), 0xFFFu);
  EXPECT_EQ(census_at({1, 1, 9}, 12), 0xE00FFFu);
  // At the row's left end the clamped neighbours equal the centre: not darker.
  EXPECT_EQ(census_at({0, 12, 12}, 0), 0u);
  EXPECT_EQ(pms_census_bit_count({0, 12, 12}), 24);
  EXPECT_EQ(pms_census_bit_count({1, 1, 9}), 24);
  EXPECT_EQ(pms_census_bit_count(kSquareCensus), 24);
}

TEST(Census, StoredInTheFourthColourComponentAsItsDefinitionSays) {
  const int w = 9, h = 7;
  ViewImage v = make_view_image(testing_support::random_rgb8(w, h, 7));
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      EXPECT_EQ(static_cast<std::uint32_t>(v.color[4 * (y * w + x) + 3]), census_of(v, x, y))
          << x << "," << y;
    }
  }
}

TEST(MatchingCost, CensusTermIsTheWeightedHammingDistance) {
  // One row: the uniform left image has census 0 everywhere. Right pixel 1 (90) between
  // two 50s: with rows and columns clamped, each of the 5 window rows reads the pixels
  // 0, 0, 1, 2, 2, four of them darker (the centre row skips the centre itself), so its
  // census has 20 bits set. A 1x1 window at left pixel 1 with d = 0 compares it with
  // census 0: the census term adds 0.5 * 20.
  ViewImage left = grey_row({50, 50, 50});
  ViewImage right = grey_row({50, 90, 50});
  ASSERT_EQ(census_of(left, 1, 0), 0u);
  ASSERT_EQ(std::bitset<32>(census_of(right, 1, 0)).count(), 20u);
  auto weights = make_support_weight_table(10.0f);
  const float with_census =
      cost(left, right, weights, params(0, 1, 100, 100, 0.5f), 1, 0, 0, 0, 0.0f, -1.0f);
  const float without =
      cost(left, right, weights, params(0, 1, 100, 100), 1, 0, 0, 0, 0.0f, -1.0f);
  EXPECT_NEAR(with_census - without, 10.0, 1e-4);
  // Capped at 6 bits, the 20-bit distance counts 6: 0.5 * 6; a cap above 20 changes nothing.
  const float capped =
      cost(left, right, weights, params(0, 1, 100, 100, 0.5f, 6.0f), 1, 0, 0, 0, 0.0f, -1.0f);
  EXPECT_NEAR(capped - without, 3.0, 1e-4);
  const float loose =
      cost(left, right, weights, params(0, 1, 100, 100, 0.5f, 21.0f), 1, 0, 0, 0, 0.0f, -1.0f);
  EXPECT_EQ(loose, with_census);
}

TEST(MatchingCost, AgreesWithIndependentImplementationEverywhere) {
  const int w = 23, h = 17;
  ViewImage left = make_view_image(testing_support::random_rgb8(w, h, 1));
  ViewImage right = make_view_image(testing_support::random_rgb8(w, h, 2));
  for (float gamma_distance : {INFINITY, 4.0f}) {
    auto weights = make_support_weight_table(10.0f, gamma_distance);
    for (int step : {1, 2, 3}) {
      for (int radius : {1, 4, 7}) {
        // Census off, on, and on with its distance capped at 9 bits.
        PmsCostParams p = params(radius, step, 10.0f, 2.0f, step == 2 ? 0.0f : 0.75f,
                                 step == 3 ? 9.0f : 24.0f);
        for (int y : {0, 3, h - 1}) {
          for (int x : {0, 1, 11, w - 2, w - 1}) {
            for (float direction : {-1.0f, 1.0f}) {
              double expected = reference_cost(left, right, 10.0, gamma_distance, p, x, y, 0.07,
                                               -0.05, 4.3, direction);
              float got = cost(left, right, weights, p, x, y, 0.07f, -0.05f, 4.3f, direction);
              EXPECT_NEAR(got, expected, 1e-4 * std::max(1.0, expected))
                  << "gamma_distance " << gamma_distance << " step " << step << " radius "
                  << radius << " at " << x << "," << y;
            }
          }
        }
      }
    }
  }
}

TEST(MatchingCost, BoundStopsEarlyButNeverBelowTheBound) {
  const int w = 40, h = 30;
  ViewImage left = make_view_image(testing_support::random_rgb8(w, h, 3));
  ViewImage right = make_view_image(testing_support::random_rgb8(w, h, 4));
  auto weights = make_support_weight_table(10.0f);
  PmsCostParams p = params(8, 2, 10.0f, 2.0f);
  float full = cost(left, right, weights, p, 20, 15, 0.0f, 0.0f, 5.0f, -1.0f);
  EXPECT_EQ(cost(left, right, weights, p, 20, 15, 0.0f, 0.0f, 5.0f, -1.0f, full * 2), full);
  float stopped = cost(left, right, weights, p, 20, 15, 0.0f, 0.0f, 5.0f, -1.0f, full * 0.25f);
  EXPECT_GE(stopped, full * 0.25f);
  EXPECT_LT(stopped, full);
}

TEST(WeightTable, MatchesExpAndIsMonotone) {
  auto weights = make_support_weight_table(10.0f);
  ASSERT_EQ(weights.size(), static_cast<size_t>(PMS_WEIGHT_TABLE_SIZE));
  EXPECT_EQ(weights[0], 1.0f);
  EXPECT_FLOAT_EQ(weights[10], static_cast<float>(std::exp(-1.0)));
  for (int k = 1; k < PMS_COLOR_WEIGHT_COUNT; ++k) EXPECT_LE(weights[k], weights[k - 1]);
}

TEST(WeightTable, DistanceFactorsFallWithTheOffsetAndAreOneWhenOff) {
  auto weights = make_support_weight_table(10.0f, 20.0f);
  EXPECT_EQ(pms_distance_weight_row(weights.data(), 0)[0], 1.0f);
  // Offset (3, 4) and (-3, -4) lie 5 px from the centre.
  EXPECT_FLOAT_EQ(pms_distance_weight_row(weights.data(), 4)[3],
                  static_cast<float>(std::exp(-5.0 / 20.0)));
  EXPECT_EQ(pms_distance_weight_row(weights.data(), -4)[3],
            pms_distance_weight_row(weights.data(), 4)[3]);
  // Along the table's last row, offset (50, 50) lies farther out than (49, 50).
  const float* last_row = pms_distance_weight_row(weights.data(), 50);
  EXPECT_LT(last_row[50], last_row[49]);
  auto colour_only = make_support_weight_table(10.0f);
  for (int k = PMS_COLOR_WEIGHT_COUNT; k < PMS_WEIGHT_TABLE_SIZE; ++k) {
    ASSERT_EQ(colour_only[k], 1.0f) << k;
  }
}
