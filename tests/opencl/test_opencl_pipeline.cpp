// The whole OpenCL pipeline against run_stereo on a crop of the TeddyH fixture: the raw
// disparities of both views, the filled planes and the final disparity, byte for byte.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>

#include "host/io/image_io.h"
#include "host/io/input_error.h"
#include "host/opencl/opencl_matcher.h"
#include "opencl_test_support.h"

namespace flexsight::opencl::test {
namespace {

struct PipelineCase {
  const char* name;
  StereoMethod method;
  int window;
  int median_window;
  int ndisp;
  int fill_coarse = 1;
  float median_background_margin = 2.0f;
  float fill_max_extrapolation = 2.0f;
  int window_step_fine = 4;  // StereoParams' default
  int refresh_confidence = 1;
  int iterations_fine = 2;
  int speckle_size = 100;  // StereoParams' default
  float speckle_range = 1.0f;
  int raw_speckle_size = 20;  // StereoParams' default
  int refill_iterations = 1;  // StereoParams' default
  int window_step_finest = 0;  // StereoParams' default: the finer levels' values
  int iterations_finest = 0;
  int refill_unsure_only = 1;  // StereoParams' default
};

void PrintTo(const PipelineCase& c, std::ostream* out) { *out << c.name; }

OpenClMatcher& matcher() {
  static OpenClMatcher shared([] {
    OpenClOptions options;
    const char* device = std::getenv("FLEXSIGHT_OPENCL_DEVICE");
    options.device = device ? device : "";
    options.profile = true;
    return options;
  }());
  return shared;
}

double seconds(const std::chrono::steady_clock::time_point& start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Both views' raw disparities, the filled planes, their costs and the final disparity.
void expect_same_outputs(const StereoResult& expected, const StereoResult& actual) {
  EXPECT_TRUE(testing_support::same_bytes(expected.raw_left, actual.raw_left)) << "raw_left";
  EXPECT_TRUE(testing_support::same_bytes(expected.raw_right, actual.raw_right)) << "raw_right";
  EXPECT_TRUE(testing_support::same_bytes(expected.planes_left, actual.planes_left))
      << "planes_left";
  EXPECT_TRUE(testing_support::same_bytes(expected.cost_left, actual.cost_left)) << "cost_left";
  EXPECT_TRUE(testing_support::same_bytes(expected.disparity, actual.disparity)) << "disparity";
}

class Pipeline : public ::testing::TestWithParam<PipelineCase> {};

TEST_P(Pipeline, MatchesTheReferenceByteForByte) {
  const PipelineCase c = GetParam();
  const testing_support::FixtureCrop crop = testing_support::fixture_crop();
  StereoParams params;
  params.method = c.method;
  params.ndisp = c.ndisp;
  params.window = c.window;
  params.median_window = c.median_window;
  params.fill_coarse = c.fill_coarse;
  params.median_background_margin = c.median_background_margin;
  params.fill_max_extrapolation = c.fill_max_extrapolation;
  params.window_step_fine = c.window_step_fine;
  params.refresh_confidence = c.refresh_confidence;
  params.iterations_fine = c.iterations_fine;
  params.speckle_size = c.speckle_size;
  params.speckle_range = c.speckle_range;
  params.raw_speckle_size = c.raw_speckle_size;
  params.refill_iterations = c.refill_iterations;
  params.window_step_finest = c.window_step_finest;
  params.iterations_finest = c.iterations_finest;
  params.refill_unsure_only = c.refill_unsure_only;
  params.coarsest_width = 40;

  OpenClMatcher& opencl = matcher();  // built first: program builds are not timed
  auto start = std::chrono::steady_clock::now();
  const StereoResult expected = run_stereo(crop.left, crop.right, params);
  const double reference_seconds = seconds(start);
  start = std::chrono::steady_clock::now();
  const StereoResult actual = opencl.run(crop.left, crop.right, params);
  const double opencl_seconds = seconds(start);

  expect_same_outputs(expected, actual);
  ASSERT_EQ(expected.timings.size(), actual.timings.size());
  for (size_t i = 0; i < expected.timings.size(); ++i) {
    EXPECT_EQ(expected.timings[i].stage, actual.timings[i].stage);
  }

  // Not a check: the numbers for the record (ctest -V shows them).
  std::printf("[ timing   ] %s on %s: reference %.3f s, OpenCL %.3f s\n", c.name,
              opencl.device_description().c_str(), reference_seconds, opencl_seconds);
  for (const KernelTiming& t : opencl.kernel_timings()) {
    std::printf("[ timing   ]   %-24s %5d launches %9.3f ms\n", t.kernel.c_str(), t.launches,
                t.seconds * 1e3);
  }
}

// The memory yardstick: device buffers at most 10x the input pair (RGB8) plus
// the planes of both views (3 floats each), i.e. 300 bytes per pixel. Measured: about
// 5x (pyramid, both views' planes, costs and post-processing buffers).
TEST(PipelineMemory, DeviceBuffersStayWithinTenTimesTheInputPairAndItsPlanes) {
  const testing_support::FixtureCrop crop = testing_support::fixture_crop();
  StereoParams params;
  params.ndisp = 32;
  matcher().run(crop.left, crop.right, params);
  const double pixels = static_cast<double>(crop.left.total());
  const double yardstick = 30.0 * pixels;
  EXPECT_GT(matcher().peak_buffer_bytes(), 2 * yardstick) << "the counter counts something";
  EXPECT_LE(matcher().peak_buffer_bytes(), 10 * yardstick);
}

// The fast preset (apply_stereo_preset) sets window steps of 3, 5 and 6 and one iteration
// per finer level, values no case above combines: the same bytes on every output.
TEST(PipelinePresets, FastPresetMatchesTheReferenceByteForByte) {
  const testing_support::FixtureCrop crop = testing_support::fixture_crop();
  StereoParams params;
  ASSERT_TRUE(apply_stereo_preset("fast", params));
  params.ndisp = 32;
  params.coarsest_width = 40;
  const StereoResult expected = run_stereo(crop.left, crop.right, params);
  const StereoResult actual = matcher().run(crop.left, crop.right, params);
  expect_same_outputs(expected, actual);
}

TEST(PipelineInputs, InvalidInputsThrowAsInTheReference) {
  const testing_support::FixtureCrop crop = testing_support::fixture_crop();
  StereoParams params;
  params.ndisp = 500;
  EXPECT_THROW(matcher().run(crop.left, crop.right, params), InputError);
  params.ndisp = 32;
  EXPECT_THROW(matcher().run(crop.left, crop.right(cv::Rect(0, 0, 100, 93)), params), InputError);
}

INSTANTIATE_TEST_SUITE_P(
    TeddyCrop, Pipeline,
    ::testing::Values(PipelineCase{"ppms_w11", StereoMethod::PPMS, 11, 11, 32},
                      PipelineCase{"pms_w11", StereoMethod::PMS, 11, 11, 32},
                      PipelineCase{"ppms_default_windows", StereoMethod::PPMS, 35, 35, 48},
                      PipelineCase{"ppms_w11_no_coarse_fill_every_vote", StereoMethod::PPMS, 11,
                                   11, 32, 0, INFINITY},
                      PipelineCase{"ppms_w11_plain_extrapolation", StereoMethod::PPMS, 11, 11, 32,
                                   1, 2.0f, INFINITY},
                      PipelineCase{"ppms_w11_one_window_step", StereoMethod::PPMS, 11, 11, 32,
                                   1, 2.0f, 2.0f, 2},
                      PipelineCase{"ppms_w11_fine_step_3", StereoMethod::PPMS, 11, 11, 32, 1,
                                   2.0f, 2.0f, 3},
                      PipelineCase{"ppms_w11_carried_confidence_only", StereoMethod::PPMS, 11,
                                   11, 32, 1, 2.0f, 2.0f, 4, 0},
                      PipelineCase{"ppms_w11_three_fine_iterations", StereoMethod::PPMS, 11, 11,
                                   32, 1, 2.0f, 2.0f, 4, 1, 3},
                      PipelineCase{"ppms_w11_no_speckle_refill", StereoMethod::PPMS, 11, 11, 32,
                                   1, 2.0f, 2.0f, 4, 1, 2, 0, 1.0f, 0},
                      PipelineCase{"ppms_w11_raw_speckles_only", StereoMethod::PPMS, 11, 11, 32,
                                   1, 2.0f, 2.0f, 4, 1, 2, 0, 1.0f, 60},
                      PipelineCase{"ppms_w11_large_fine_speckles", StereoMethod::PPMS, 11, 11,
                                   32, 1, 2.0f, 2.0f, 4, 1, 2, 400, 0.5f},
                      PipelineCase{"ppms_w11_no_refill", StereoMethod::PPMS, 11, 11, 32, 1,
                                   2.0f, 2.0f, 4, 1, 2, 100, 1.0f, 20, 0},
                      PipelineCase{"ppms_w11_two_refills_no_refresh", StereoMethod::PPMS, 11,
                                   11, 32, 1, 2.0f, 2.0f, 4, 0, 2, 100, 1.0f, 20, 2},
                      PipelineCase{"pms_w11_no_refill", StereoMethod::PMS, 11, 11, 32, 1, 2.0f,
                                   2.0f, 4, 1, 2, 100, 1.0f, 20, 0},
                      PipelineCase{"ppms_w11_finest_step_5_one_iteration", StereoMethod::PPMS,
                                   11, 11, 32, 1, 2.0f, 2.0f, 4, 1, 2, 100, 1.0f, 20, 1, 5, 1},
                      PipelineCase{"ppms_w11_refill_every_pixel", StereoMethod::PPMS, 11, 11, 32,
                                   1, 2.0f, 2.0f, 4, 1, 2, 100, 1.0f, 20, 1, 0, 0, 0},
                      PipelineCase{"pms_w11_refill_every_pixel", StereoMethod::PMS, 11, 11, 32, 1,
                                   2.0f, 2.0f, 4, 1, 2, 100, 1.0f, 20, 1, 0, 0, 0}),
    [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace flexsight::opencl::test
