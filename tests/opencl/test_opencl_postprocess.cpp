// The post-processing kernels against fallback/postprocess_reference.cpp, byte for
// byte, with a guard region after every output.
#include <gtest/gtest.h>

#include <random>

#include "fallback/postprocess_reference.h"
#include "opencl_test_support.h"

namespace flexsight::opencl::test {
namespace {

// Disparities of both views where about a third of the left pixels agree exactly with
// the right pixel they point at, a third nearly (within or just past the tolerance) and
// a third not at all; some point outside the image.
struct DisparityPair {
  std::vector<float> left;
  std::vector<float> right;
};

DisparityPair random_disparities(int width, int height, int ndisp, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> d(0.0f, static_cast<float>(ndisp - 1));
  std::uniform_int_distribution<int> kind(0, 2);
  std::uniform_real_distribution<float> offset(-1.5f, 1.5f);
  DisparityPair pair;
  pair.right.resize(static_cast<size_t>(width) * height);
  for (float& v : pair.right) v = d(rng);
  pair.left.resize(pair.right.size());
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      float value = d(rng);
      float match = pms_floor_round(static_cast<float>(x) - value);
      int k = kind(rng);
      if (k < 2 && match >= 0.0f && match <= static_cast<float>(width - 1)) {
        float other = pair.right[y * width + static_cast<int>(match)];
        value = k == 0 ? other : std::max(0.0f, other + offset(rng));
      }
      pair.left[y * width + x] = value;
    }
  }
  return pair;
}

// Consistency flags where a row is all consistent, all inconsistent or mixed.
std::vector<std::uint8_t> random_consistency(int width, int height, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> row_kind(0, 4);
  std::bernoulli_distribution bit(0.6);
  std::vector<std::uint8_t> consistent(static_cast<size_t>(width) * height);
  for (int y = 0; y < height; ++y) {
    int kind = row_kind(rng);
    for (int x = 0; x < width; ++x) {
      consistent[y * width + x] =
          kind == 0 ? 0 : kind == 1 ? 1 : static_cast<std::uint8_t>(bit(rng));
    }
  }
  return consistent;
}

class PostProcessStage : public ::testing::TestWithParam<LevelCase> {};

TEST_P(PostProcessStage, LeftRightCheck) {
  const LevelCase c = GetParam();
  const DisparityPair pair = random_disparities(c.width, c.height, c.ndisp, c.seed);
  const Buffer<float> left = guarded(pair.left, "left");
  const Buffer<float> right = guarded(pair.right, "right");
  for (float tolerance : {0.0f, 0.5f, 1.0f}) {
    const std::vector<std::uint8_t> expected =
        left_right_check(pair.left, pair.right, c.width, c.height, tolerance, 2);
    Buffer<std::uint8_t> consistent = guarded_output<std::uint8_t>(expected.size(), "consistent");
    stages().left_right_check(left, right, c.width, c.height, tolerance, consistent);
    EXPECT_TRUE(same_buffer(expected, consistent)) << "tolerance " << tolerance;
  }
}

TEST_P(PostProcessStage, FillInconsistent) {
  const LevelCase c = GetParam();
  LevelFixture f(c);
  const std::vector<std::uint8_t> consistent = random_consistency(c.width, c.height, c.seed);
  const std::vector<float> expected =
      fill_inconsistent(f.fields[0].planes, consistent, c.width, c.height, 2);
  Buffer<float> filled = guarded_output<float>(expected.size(), "filled");
  stages().fill_inconsistent(guarded(f.fields[0].planes, "planes"),
                             guarded(consistent, "consistent"), c.width, c.height, filled);
  EXPECT_TRUE(same_buffer(expected, filled));
}

TEST_P(PostProcessStage, WeightedMedianFilled) {
  const LevelCase c = GetParam();
  LevelFixture f(c);
  const std::vector<float> disparity = plane_disparities(f.fields[0], 2);
  const std::vector<std::uint8_t> consistent = random_consistency(c.width, c.height, c.seed + 1);
  const std::vector<float> weights = make_support_weight_table(7.5f);
  const int radius = c.window / 2;
  const std::vector<float> expected = weighted_median_filled(
      disparity, consistent, f.images[PMS_VIEW_LEFT], weights.data(), radius, c.step, 2);
  Buffer<float> filtered = guarded_output<float>(expected.size(), "filtered");
  stages().weighted_median_filled(guarded(disparity, "disparity"),
                                  guarded(consistent, "consistent"),
                                  f.device_images[PMS_VIEW_LEFT], guarded(weights, "weights"),
                                  radius, c.step, filtered);
  EXPECT_TRUE(same_buffer(expected, filtered));
}

INSTANTIATE_TEST_SUITE_P(Cases, PostProcessStage, ::testing::ValuesIn(level_cases()),
                         level_case_name);

}  // namespace
}  // namespace flexsight::opencl::test
