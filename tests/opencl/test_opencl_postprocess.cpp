// The post-processing kernels against fallback/postprocess_reference.cpp, byte for
// byte, with a guard region after every output; inputs from tests/kernel_cases.h.
#include <gtest/gtest.h>

#include "fallback/postprocess_reference.h"
#include "opencl_test_support.h"

namespace flexsight::opencl::test {
namespace {

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
  const MedianInputs m = median_inputs(f, c);
  const std::vector<float> expected = weighted_median_filled(
      m.disparity, m.consistent, f.images[PMS_VIEW_LEFT], m.weights.data(), m.radius, m.step, 2);
  Buffer<float> filtered = guarded_output<float>(expected.size(), "filtered");
  stages().weighted_median_filled(guarded(m.disparity, "disparity"),
                                  guarded(m.consistent, "consistent"),
                                  f.device_images[PMS_VIEW_LEFT], guarded(m.weights, "weights"),
                                  m.radius, m.step, filtered);
  EXPECT_TRUE(same_buffer(expected, filtered));
}

TEST_P(PostProcessStage, WeightedMedianAll) {
  const LevelCase c = GetParam();
  LevelFixture f(c);
  const MedianInputs m = median_inputs(f, c);
  for (int radius : {0, 1, 3}) {
    const std::vector<float> expected =
        weighted_median_all(m.disparity, f.images[PMS_VIEW_LEFT], m.weights.data(), radius, 2);
    Buffer<float> filtered = guarded_output<float>(expected.size(), "filtered");
    stages().weighted_median_all(guarded(m.disparity, "disparity"),
                                 f.device_images[PMS_VIEW_LEFT], guarded(m.weights, "weights"),
                                 radius, filtered);
    EXPECT_TRUE(same_buffer(expected, filtered)) << "radius " << radius;
  }
}

INSTANTIATE_TEST_SUITE_P(Cases, PostProcessStage, ::testing::ValuesIn(level_cases()),
                         level_case_name);

}  // namespace
}  // namespace flexsight::opencl::test
