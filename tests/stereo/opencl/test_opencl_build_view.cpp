// Pyramid levels on the device against fallback/stereo/image_pyramid.cpp, byte for byte.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "tests/stereo/opencl/opencl_test_support.h"

namespace flexsight::opencl::test {
namespace {

struct ImageCase {
  int width;
  int height;
  unsigned seed;
};

std::string size_name(const ImageCase& c) {
  return std::to_string(c.width) + "x" + std::to_string(c.height);
}
void PrintTo(const ImageCase& c, std::ostream* out) { *out << size_name(c); }

class BuildView : public ::testing::TestWithParam<ImageCase> {};

TEST_P(BuildView, GradientMatchesTheReference) {
  const ImageCase c = GetParam();
  const ViewImage image = make_view_image(testing_support::random_rgb8(c.width, c.height, c.seed));
  DeviceView view{image.width, image.height, guarded(image.color, "colour"),
                  guarded_output<float>(image.gradient.size(), "gradient")};
  stages().compute_gradient(view);
  EXPECT_TRUE(same_buffer(image.gradient, view.gradient));
  EXPECT_TRUE(same_buffer(image.color, view.color)) << "the colour is an input";
}

TEST_P(BuildView, DownsampleMatchesTheReference) {
  const ImageCase c = GetParam();
  const ViewImage fine = make_view_image(testing_support::random_rgb8(c.width, c.height, c.seed));
  const ViewImage expected = downsample(fine);
  const DeviceView device_fine = upload(fine, "fine");
  DeviceView coarse{expected.width, expected.height,
                    guarded_output<float>(expected.color.size(), "coarse colour"),
                    guarded_output<float>(expected.gradient.size(), "coarse gradient")};
  stages().downsample_color(device_fine, coarse);
  stages().compute_gradient(coarse);
  EXPECT_TRUE(same_buffer(expected.color, coarse.color));
  EXPECT_TRUE(same_buffer(expected.gradient, coarse.gradient));
}

// Census neighbourhoods other than the default 5x5 (PmsCensusShape): the centre row
// only, a 3x3 square with a 19-px centre row, 3x7, and a lone pair of row neighbours.
TEST_P(BuildView, OtherCensusShapesMatchTheReference) {
  const ImageCase c = GetParam();
  const cv::Mat rgb8 = testing_support::random_rgb8(c.width, c.height, c.seed);
  for (const PmsCensusShape shape : {PmsCensusShape{0, 12, 12}, PmsCensusShape{1, 1, 9},
                                     PmsCensusShape{1, 3, 3}, PmsCensusShape{0, 1, 1}}) {
    const ViewImage image = make_view_image(rgb8, shape);
    if (c.width >= 7 && c.height >= 5) {
      EXPECT_NE(image.color, make_view_image(rgb8).color) << "the shape changes the census";
    }
    DeviceView view{image.width, image.height, guarded(image.color, "colour"),
                    guarded_output<float>(image.gradient.size(), "gradient")};
    stages().compute_gradient(view, shape);
    EXPECT_TRUE(same_buffer(image.gradient, view.gradient));
    EXPECT_TRUE(same_buffer(image.color, view.color)) << shape.half_rows << "," << shape.half_cols
                                                      << "," << shape.half_row_length;
  }
}

// The records are a device-only layout: written out here from their definition.
std::vector<float> expected_match_records(const ViewImage& image) {
  std::vector<float> records;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const size_t at = static_cast<size_t>(y) * image.width + x;
      const size_t next = static_cast<size_t>(y) * image.width + std::min(x + 1, image.width - 1);
      const float* c0 = &image.color[4 * at];
      const float* c1 = &image.color[4 * next];
      const float* g0 = &image.gradient[2 * at];
      const float* g1 = &image.gradient[2 * next];
      const float record[PMS_MATCH_RECORD] = {c0[0], c0[1], c0[2], c0[3],
                                              c1[0] - c0[0], c1[1] - c0[1], c1[2] - c0[2], c1[3],
                                              g0[0], g0[1], g1[0] - g0[0], g1[1] - g0[1]};
      records.insert(records.end(), record, record + PMS_MATCH_RECORD);
    }
  }
  records.insert(records.end(), 4, 0.0f);  // read past the last record, never used
  return records;
}

TEST_P(BuildView, MatchRecordsHoldTheSamplesAtXAndTheStepsToXPlusOne) {
  const ImageCase c = GetParam();
  const ViewImage image = make_view_image(testing_support::random_rgb8(c.width, c.height, c.seed));
  const std::vector<float> expected = expected_match_records(image);
  ASSERT_EQ(expected.size(), match_record_floats(static_cast<size_t>(c.width) * c.height));
  const DeviceView view = upload(image, "view");
  Buffer<float> match = guarded_output<float>(expected.size(), "match records");
  stages().pack_match_samples(view, match);
  EXPECT_TRUE(same_buffer(expected, match));
}

INSTANTIATE_TEST_SUITE_P(Sizes, BuildView,
                         ::testing::Values(ImageCase{1, 1, 1}, ImageCase{2, 2, 2},
                                           ImageCase{7, 5, 3}, ImageCase{1, 9, 4},
                                           ImageCase{9, 1, 5}, ImageCase{33, 17, 6},
                                           ImageCase{131, 93, 7}, ImageCase{64, 48, 8}),
                         [](const auto& info) { return size_name(info.param); });

}  // namespace
}  // namespace flexsight::opencl::test
