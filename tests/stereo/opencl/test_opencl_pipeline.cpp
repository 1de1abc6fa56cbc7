// The whole OpenCL pipeline against run_stereo on a crop of the TeddyH fixture: the raw
// disparities of both views, the filled planes and the final disparity, byte for byte.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <memory>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "host/io/image_io.h"
#include "host/io/input_error.h"
#include "host/runtime/shared_context.h"
#include "host/stereo/opencl_matcher.h"
#include "tests/stereo/opencl/opencl_test_support.h"

namespace flexsight::opencl::test {
namespace {

// One configuration of the whole pipeline, named for the fields it changes.
struct PipelineCase {
  const char* name;
  StereoParams params;
};

void PrintTo(const PipelineCase& c, std::ostream* out) { *out << c.name; }

// The cases' common ground: StereoParams' defaults on the 131x93 crop, with a 40-px
// coarsest level so that PPMS has levels below it, and the filled disparity held within
// 2 px of its source (fill_max_extrapolation; the 4-px default runs in
// PipelinePresets). `window` is both the support window and the hole median's.
StereoParams crop_params(StereoMethod method, int window = 11, int ndisp = 32) {
  StereoParams p;
  p.method = method;
  p.ndisp = ndisp;
  p.window = window;
  p.median_window = window;
  p.fill_max_extrapolation = 2.0f;
  p.coarsest_width = 40;
  return p;
}

// Every case: one switch of the pipeline (a stage off, a limit lifted, a knob at another
// value) or two that interact, on the common ground above.
std::vector<PipelineCase> pipeline_cases() {
  std::vector<PipelineCase> cases;
  const auto add = [&cases](const char* name, StereoParams p) { cases.push_back({name, p}); };
  const auto ppms = [](auto change) {
    StereoParams p = crop_params(StereoMethod::PPMS);
    change(p);
    return p;
  };
  const auto pms = [](auto change) {
    StereoParams p = crop_params(StereoMethod::PMS);
    change(p);
    return p;
  };
  add("ppms_w11", crop_params(StereoMethod::PPMS));
  add("pms_w11", crop_params(StereoMethod::PMS));
  add("ppms_default_windows", crop_params(StereoMethod::PPMS, 35, 48));
  add("ppms_w11_no_coarse_fill_every_vote", ppms([](StereoParams& p) {
        p.fill_coarse = false;
        p.median_background_margin = INFINITY;
      }));
  add("ppms_w11_plain_extrapolation",
      ppms([](StereoParams& p) { p.fill_max_extrapolation = INFINITY; }));
  add("ppms_w11_one_window_step", ppms([](StereoParams& p) { p.window_step_fine = 2; }));
  add("ppms_w11_fine_step_3", ppms([](StereoParams& p) { p.window_step_fine = 3; }));
  add("ppms_w11_carried_confidence_only",
      ppms([](StereoParams& p) { p.refresh_confidence = false; }));
  add("ppms_w11_three_fine_iterations", ppms([](StereoParams& p) { p.iterations_fine = 3; }));
  add("ppms_w11_no_speckle_refill", ppms([](StereoParams& p) {
        p.speckle_size = 0;
        p.raw_speckle_size = 0;
      }));
  add("ppms_w11_raw_speckles_only", ppms([](StereoParams& p) {
        p.speckle_size = 0;
        p.raw_speckle_size = 60;
      }));
  add("ppms_w11_large_fine_speckles", ppms([](StereoParams& p) {
        p.speckle_size = 400;
        p.speckle_range = 0.5f;
      }));
  add("ppms_w11_no_refill", ppms([](StereoParams& p) { p.refill_iterations = 0; }));
  add("ppms_w11_two_refills_no_refresh", ppms([](StereoParams& p) {
        p.refresh_confidence = false;
        p.refill_iterations = 2;
      }));
  add("pms_w11_no_refill", pms([](StereoParams& p) { p.refill_iterations = 0; }));
  add("ppms_w11_finest_step_5_one_iteration", ppms([](StereoParams& p) {
        p.window_step_finest = 5;
        p.iterations_finest = 1;
      }));
  add("ppms_w11_refill_every_pixel", ppms([](StereoParams& p) { p.refill_unsure_only = false; }));
  add("pms_w11_refill_every_pixel", pms([](StereoParams& p) { p.refill_unsure_only = false; }));
  // The textured-pixel mask (uploaded from the host) gating the check before the fill.
  add("ppms_w11_textureless_gate", ppms([](StereoParams& p) { p.textureless_spread = 12.0f; }));
  // Both segment steps joining steps that continue a slope (large raw segments too, so
  // that the raw step changes the check).
  add("ppms_w11_speckles_follow_slopes", ppms([](StereoParams& p) {
        p.speckle_slopes = true;
        p.raw_speckle_size = 60;
      }));
  // Other census neighbourhoods (StereoParams::census_rows / cols / row_length): the
  // centre row only, and a 3x3 square with a 19-px centre row.
  add("ppms_w11_row_census", ppms([](StereoParams& p) {
        p.census_rows = 1;
        p.census_cols = 25;
        p.census_row_length = 25;
      }));
  add("ppms_w11_census_3x3_row_19", ppms([](StereoParams& p) {
        p.census_rows = 3;
        p.census_cols = 3;
        p.census_row_length = 19;
      }));
  // A support window wider than tall (StereoParams::window_rows).
  add("ppms_w11_window_5_rows", ppms([](StereoParams& p) { p.window_rows = 5; }));
  return cases;
}

OpenClMatcher& matcher() {
  static OpenClMatcher shared([] {
    OpenClOptions options;
    const char* device = std::getenv("FLEXSIGHT_OPENCL_DEVICE");
    options.cl_device = device ? device : "";
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
  const PipelineCase& c = GetParam();
  const testing_support::FixtureCrop crop = testing_support::fixture_crop();
  const StereoParams& params = c.params;

  OpenClMatcher& opencl = matcher();  // built first: program builds are not timed
  auto start = std::chrono::steady_clock::now();
  const StereoResult expected = run_stereo(crop.left, crop.right, params);
  const double reference_seconds = seconds(start);
  start = std::chrono::steady_clock::now();
  const StereoResult actual = opencl.run(crop.left, crop.right, params);
  const double opencl_seconds = seconds(start);

  // The times go with a failure's message, where they tell a wrong result from a
  // stalled or skipped stage; the benchmarks (bench/) are where speed is measured.
  std::ostringstream times;
  times << c.name << " on " << opencl.device_description() << ": reference "
        << reference_seconds << " s, OpenCL " << opencl_seconds << " s";
  for (const KernelTiming& t : opencl.kernel_timings()) {
    times << "; " << t.kernel << " " << t.launches << "x " << t.seconds * 1e3 << " ms";
  }
  SCOPED_TRACE(times.str());
  expect_same_outputs(expected, actual);
  ASSERT_EQ(expected.timings.size(), actual.timings.size());
  for (size_t i = 0; i < expected.timings.size(); ++i) {
    EXPECT_EQ(expected.timings[i].stage, actual.timings[i].stage);
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

// The projector-lit preset: raised truncations, the textureless gate, every vote, no
// extrapolation in the fill.
TEST(PipelinePresets, ActivePresetMatchesTheReferenceByteForByte) {
  const testing_support::FixtureCrop crop = testing_support::fixture_crop();
  StereoParams params;
  ASSERT_TRUE(apply_stereo_preset("active", params));
  ASSERT_GT(params.textureless_spread, 0.0f);
  params.ndisp = 32;
  params.coarsest_width = 40;
  const StereoResult expected = run_stereo(crop.left, crop.right, params);
  const StereoResult actual = matcher().run(crop.left, crop.right, params);
  expect_same_outputs(expected, actual);
  // The gate found windows without texture on the crop and changed what was filled.
  StereoParams ungated = params;
  ungated.textureless_spread = 0.0f;
  EXPECT_FALSE(testing_support::same_bytes(expected.planes_left, run_stereo(crop.left, crop.right, ungated).planes_left));
}

// The camera runs the matcher and the detector's post-processing on one device
// context (host/runtime/shared_context.h): another module's program built into the
// context first, the matcher built on the same context adds its programs beside it,
// gives the reference's bytes, and its buffers are counted on that context.
TEST(SharedContext, AMatcherOnAContextAnotherModuleUsesGivesTheReferenceBytes) {
  BackendOptions options;
  const char* device = std::getenv("FLEXSIGHT_OPENCL_DEVICE");
  options.cl_device = device ? device : "";
  const std::shared_ptr<Context> shared = open_shared_context(options);
  const KernelSource other_module = {
      "other_module.cl", 0x5eed,
      "__kernel void other(__global float* out) { out[get_global_id(0)] = 1.0f; }"};
  shared->program(other_module);
  ASSERT_EQ(shared->programs().size(), 1u);

  OpenClMatcher on_shared(shared);
  EXPECT_GT(shared->programs().size(), 1u) << "the matcher's programs join the context's";
  const testing_support::FixtureCrop crop = testing_support::fixture_crop();
  StereoParams params;
  params.ndisp = 32;
  params.coarsest_width = 40;
  const StereoResult expected = run_stereo(crop.left, crop.right, params);
  expect_same_outputs(expected, on_shared.run(crop.left, crop.right, params));
  EXPECT_GT(shared->peak_buffer_bytes(), 0u);
  EXPECT_EQ(on_shared.peak_buffer_bytes(), shared->peak_buffer_bytes());
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
    TeddyCrop, Pipeline, ::testing::ValuesIn(pipeline_cases()),
    [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace flexsight::opencl::test
