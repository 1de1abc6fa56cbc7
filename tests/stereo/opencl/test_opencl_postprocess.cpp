// The post-processing kernels against fallback/stereo/postprocess_reference.cpp, byte for
// byte, with a guard region after every output; inputs from tests/stereo/kernel_cases.h.
#include <gtest/gtest.h>
#include <cfloat>
#include <map>
#include <memory>
#include <random>
#include <tuple>

#include "fallback/stereo/postprocess_reference.h"
#include "tests/stereo/opencl/opencl_test_support.h"

namespace flexsight::opencl::test {
namespace {

class PostProcessStage : public ::testing::TestWithParam<LevelCase> {};

TEST_P(PostProcessStage, LeftRightCheck) {
  const LevelCase c = GetParam();
  const DisparityPair pair = random_disparities(c.width, c.height, c.ndisp, c.seed);
  const Buffer<float> left = guarded(pair.left, "left");
  const Buffer<float> right = guarded(pair.right, "right");
  for (int view : {PMS_VIEW_LEFT, PMS_VIEW_RIGHT}) {
    const std::vector<float>& own = view == PMS_VIEW_LEFT ? pair.left : pair.right;
    const std::vector<float>& other = view == PMS_VIEW_LEFT ? pair.right : pair.left;
    for (float tolerance : {0.0f, 0.5f, 1.0f}) {
      const std::vector<std::uint8_t> expected =
          left_right_check(own, other, c.width, c.height, view, tolerance, 2);
      Buffer<std::uint8_t> consistent =
          guarded_output<std::uint8_t>(expected.size(), "consistent");
      stages().left_right_check(view == PMS_VIEW_LEFT ? left : right,
                                view == PMS_VIEW_LEFT ? right : left, c.width, c.height, view,
                                tolerance, consistent);
      EXPECT_TRUE(same_buffer(expected, consistent)) << "view " << view << ", tolerance "
                                                     << tolerance;
    }
  }
}

TEST_P(PostProcessStage, FillInconsistent) {
  const LevelCase c = GetParam();
  LevelFixture f(c);
  const std::vector<std::uint8_t> consistent = random_consistency(c.width, c.height, c.seed);
  // INFINITY: plain extrapolation; 0: the source's own disparity; 1.5: limited.
  for (float limit : {INFINITY, 0.0f, 1.5f}) {
    const std::vector<float> expected =
        fill_inconsistent(f.fields[0].planes, consistent, c.width, c.height, limit, 2);
    Buffer<float> filled = guarded_output<float>(expected.size(), "filled");
    stages().fill_inconsistent(guarded(f.fields[0].planes, "planes"),
                               guarded(consistent, "consistent"), c.width, c.height, limit,
                               filled);
    EXPECT_TRUE(same_buffer(expected, filled)) << "limit " << limit;
  }
}

TEST_P(PostProcessStage, WeightedMedianFilled) {
  const LevelCase c = GetParam();
  LevelFixture f(c);
  const MedianInputs m = median_inputs(f, c);
  // 0: only votes at or behind the filled disparity; FLT_MAX: every consistent vote.
  for (float margin : {0.0f, m.background_margin, FLT_MAX}) {
    const std::vector<float> expected =
        weighted_median_filled(m.disparity, m.consistent, f.images[PMS_VIEW_LEFT],
                               m.weights.data(), m.radius, m.step, margin, 2);
    Buffer<float> filtered = guarded_output<float>(expected.size(), "filtered");
    stages().weighted_median_filled(guarded(m.disparity, "disparity"),
                                    guarded(m.consistent, "consistent"),
                                    f.device_images[PMS_VIEW_LEFT], guarded(m.weights, "weights"),
                                    m.radius, m.step, margin, filtered);
    EXPECT_TRUE(same_buffer(expected, filtered)) << "margin " << margin;
  }
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

// Disparity maps with segments of many sizes. 0: diagonal bands 1.5 px apart with
// random islands 5 px above them; 1: one constant segment; 2: a serpentine path of 0
// through a field of 5, one segment that takes many merge rounds to join; 3: a steep
// wall (2 px a row, 0.8 a column) with noise of up to 0.7 px and the islands of 0, for
// the segments that follow slopes.
std::vector<float> segment_map(int width, int height, std::uint32_t seed, int kind) {
  std::mt19937 rng(seed);
  std::bernoulli_distribution island(0.1);
  std::uniform_real_distribution<float> noise(-0.7f, 0.7f);
  std::vector<float> d(static_cast<size_t>(width) * height, 7.0f);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      float& v = d[y * width + x];
      if (kind == 0) {
        v = 1.5f * static_cast<float>((x + 2 * y) / 7) + (island(rng) ? 5.0f : 0.0f);
      } else if (kind == 2) {
        const bool open_row = y % 2 == 0;
        const bool link = (y % 4 == 1 && x == width - 1) || (y % 4 == 3 && x == 0);
        v = open_row || link ? 0.0f : 5.0f;
      } else if (kind == 3) {
        v = 2.0f * static_cast<float>(y) + 0.8f * static_cast<float>(x) + noise(rng) +
            (island(rng) ? 5.0f : 0.0f);
      }
    }
  }
  return d;
}

TEST_P(PostProcessStage, LargeSegmentMask) {
  const LevelCase c = GetParam();
  for (int kind : {0, 1, 2, 3}) {
    const std::vector<float> d = segment_map(c.width, c.height, c.seed, kind);
    const Buffer<float> disparity = guarded(d, "disparity");
    for (bool follow_slopes : {false, true}) {
      for (float max_step : {0.0f, 1.0f, 2.0f}) {
        for (int min_size : {0, 1, 2, 5, 40, c.width * c.height}) {
          const std::vector<std::uint8_t> expected =
              large_segment_mask(d, c.width, c.height, max_step, min_size, follow_slopes);
          Buffer<std::uint8_t> large = guarded_output<std::uint8_t>(expected.size(), "large");
          stages().large_segment_mask(disparity, c.width, c.height, max_step, follow_slopes,
                                      min_size, large);
          EXPECT_TRUE(same_buffer(expected, large))
              << "map " << kind << ", step " << max_step << ", size " << min_size
              << ", slopes " << follow_slopes;
        }
      }
    }
  }
}

TEST_P(PostProcessStage, MaskAnd) {
  const LevelCase c = GetParam();
  const std::vector<std::uint8_t> other = random_consistency(c.width, c.height, c.seed);
  std::vector<std::uint8_t> expected = random_consistency(c.width, c.height, c.seed + 7);
  Buffer<std::uint8_t> mask = guarded(expected, "mask");
  mask_and(expected, other);
  stages().mask_and(guarded(other, "other"), c.width, c.height, mask);
  EXPECT_TRUE(same_buffer(expected, mask));
}

TEST_P(PostProcessStage, FlatPlanes) {
  const LevelCase c = GetParam();
  const DisparityPair pair = random_disparities(c.width, c.height, c.ndisp, c.seed);
  const std::vector<float> expected = flat_planes(pair.left);
  Buffer<float> planes = guarded_output<float>(expected.size(), "planes");
  stages().flat_planes(guarded(pair.left, "disparity"), c.width, c.height, planes);
  EXPECT_TRUE(same_buffer(expected, planes));
}

INSTANTIATE_TEST_SUITE_P(Cases, PostProcessStage, ::testing::ValuesIn(level_cases()),
                         level_case_name);

// The final median runs PMS_LANES pixels per work item (the cost kernels' lane count,
// a build option) and finds the median without sorting; with 1 lane, one pixel per item
// and the sort. Both against the reference, on distinct disparities and on disparities
// quantised to 4 values, where ties decide the answer.
class MedianLanes : public ::testing::TestWithParam<std::tuple<int, LevelCase>> {};

TEST_P(MedianLanes, WeightedMedianAllMatchesTheReference) {
  const int lanes = std::get<0>(GetParam());
  const LevelCase& c = std::get<1>(GetParam());
  static std::map<int, std::unique_ptr<OpenClStages>> built_with;
  std::unique_ptr<OpenClStages>& built = built_with[lanes];
  if (!built) built = std::make_unique<OpenClStages>(context(), nullptr, lanes);
  LevelFixture f(c);
  const MedianInputs m = median_inputs(f, c);
  std::vector<float> quantised(m.disparity.size());
  for (size_t i = 0; i < quantised.size(); ++i) {
    quantised[i] = 0.5f * static_cast<float>(static_cast<int>(m.disparity[i]) % 4);
  }
  const std::vector<float>* inputs[] = {&m.disparity, &quantised};
  for (const std::vector<float>* disparity : inputs) {
    for (int radius : {0, 1, 3}) {
      const std::vector<float> expected =
          weighted_median_all(*disparity, f.images[PMS_VIEW_LEFT], m.weights.data(), radius, 2);
      Buffer<float> filtered = guarded_output<float>(expected.size(), "filtered");
      built->weighted_median_all(guarded(*disparity, "disparity"),
                                 f.device_images[PMS_VIEW_LEFT], guarded(m.weights, "weights"),
                                 radius, filtered);
      EXPECT_TRUE(same_buffer(expected, filtered))
          << "radius " << radius << (disparity == &quantised ? ", quantised" : "");
    }
  }
}

INSTANTIATE_TEST_SUITE_P(
    OneFourEightAndSixteen, MedianLanes,
    ::testing::Combine(::testing::Values(1, 4, 8, 16), ::testing::ValuesIn(level_cases())),
    [](const auto& info) {
      return std::to_string(std::get<0>(info.param)) + "lanes_" +
             case_name(std::get<1>(info.param));
    });

}  // namespace
}  // namespace flexsight::opencl::test
