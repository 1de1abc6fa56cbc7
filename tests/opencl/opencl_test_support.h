#pragma once
// What the OpenCL tests share: one device context per process (program builds are
// slow), buffers with a canary-filled guard region after the data, byte comparisons,
// and the reference-side inputs of a pyramid level.
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "fallback/image_pyramid.h"
#include "fallback/patchmatch_reference.h"
#include "fallback/weight_table.h"
#include "host/opencl/opencl_stages.h"
#include "test_support.h"

namespace flexsight::opencl::test {

// Elements after every buffer a kernel may write; they must keep the canary.
constexpr size_t kGuard = 64;

// The context of the device named by $FLEXSIGHT_OPENCL_DEVICE (default: first GPU,
// else first device). Throws, and so fails the calling test, when there is none.
inline Context& context() {
  static std::unique_ptr<Context> shared;
  if (!shared) {
    const char* selector = std::getenv("FLEXSIGHT_OPENCL_DEVICE");
    shared = std::make_unique<Context>(select_device(selector ? selector : ""));
  }
  return *shared;
}

inline OpenClStages& stages() {
  static std::unique_ptr<OpenClStages> shared;
  if (!shared) shared = std::make_unique<OpenClStages>(context());
  return *shared;
}

// A bit pattern no stage computes: a NaN with a payload for floats, 0xA5 for bytes.
template <typename T>
T canary();
template <>
inline float canary<float>() {
  float value;
  const std::uint32_t bits = 0x7fa5a5a5u;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}
template <>
inline std::uint8_t canary<std::uint8_t>() {
  return 0xA5;
}

// `values` followed by kGuard canaries.
template <typename T>
Buffer<T> guarded(const std::vector<T>& values, const std::string& what) {
  std::vector<T> padded(values);
  padded.resize(values.size() + kGuard, canary<T>());
  return Buffer<T>(context(), padded, what);
}

// `count` elements and the guard, all canaries (an element the kernel forgets to write
// then shows up as a difference too).
template <typename T>
Buffer<T> guarded_output(size_t count, const std::string& what) {
  return guarded(std::vector<T>(count, canary<T>()), what);
}

// The first `count` elements; fails the test when the guard after them changed.
template <typename T>
std::vector<T> read_checked(const Buffer<T>& buffer, size_t count) {
  std::vector<T> all = buffer.read();
  EXPECT_EQ(all.size(), count + kGuard) << buffer.what();
  if (all.size() != count + kGuard) return {};
  const std::vector<T> guard(kGuard, canary<T>());
  EXPECT_EQ(std::memcmp(all.data() + count, guard.data(), kGuard * sizeof(T)), 0)
      << "a kernel wrote past the end of '" << buffer.what() << "'";
  all.resize(count);
  return all;
}

// Byte comparison with the first difference in the message.
template <typename T>
::testing::AssertionResult same_bytes(const std::vector<T>& expected,
                                      const std::vector<T>& actual) {
  if (expected.size() != actual.size()) {
    return ::testing::AssertionFailure()
           << "sizes differ: " << expected.size() << " vs " << actual.size();
  }
  for (size_t i = 0; i < expected.size(); ++i) {
    if (std::memcmp(&expected[i], &actual[i], sizeof(T)) != 0) {
      return ::testing::AssertionFailure()
             << "element " << i << " of " << expected.size() << " differs: reference "
             << +expected[i] << ", OpenCL " << +actual[i];
    }
  }
  return ::testing::AssertionSuccess();
}

template <typename T>
::testing::AssertionResult same_buffer(const std::vector<T>& expected, const Buffer<T>& actual) {
  return same_bytes(expected, read_checked(actual, expected.size()));
}

inline DeviceView upload(const ViewImage& image, const std::string& what) {
  return {image.width, image.height, guarded(image.color, what + " colour"),
          guarded(image.gradient, what + " gradient")};
}

inline DeviceField upload(const PlaneField& field, const std::string& what) {
  return {field.width, field.height, guarded(field.planes, what + " planes"),
          guarded(field.cost, what + " cost")};
}

inline void expect_same_field(const PlaneField& expected, const DeviceField& actual) {
  EXPECT_TRUE(same_buffer(expected.planes, actual.planes)) << "planes";
  EXPECT_TRUE(same_buffer(expected.cost, actual.cost)) << "cost";
}

// One test case of a level stage.
struct LevelCase {
  int width;
  int height;
  int window;
  int step;
  int ndisp;
  std::uint32_t seed;
};

inline std::string case_name(const LevelCase& c) {
  return std::to_string(c.width) + "x" + std::to_string(c.height) + "_w" +
         std::to_string(c.window) + "s" + std::to_string(c.step) + "_n" +
         std::to_string(c.ndisp) + "_seed" + std::to_string(c.seed);
}
inline std::string level_case_name(const ::testing::TestParamInfo<LevelCase>& info) {
  return case_name(info.param);
}
// GoogleTest prints parameters in test names and messages; bytes would vary by build.
inline void PrintTo(const LevelCase& c, std::ostream* out) { *out << case_name(c); }

// Awkward sizes (1x1, odd widths), windows larger than the image, steps 1 to 3.
inline std::vector<LevelCase> level_cases() {
  return {{1, 1, 5, 1, 2, 1},      {7, 5, 5, 2, 4, 2},     {7, 5, 11, 1, 7, 3},
          {33, 17, 11, 2, 16, 4},  {33, 17, 35, 3, 9, 5},  {131, 93, 35, 2, 32, 6},
          {131, 93, 11, 1, 64, 7}, {64, 9, 9, 2, 24, 8}};
}

// A stereo pair of `c`'s size (the right view is the left one shifted by a few pixels,
// so that costs vary as on real images), the weight table and the reference's random
// initial planes of both views: the common starting point of the stage tests.
struct LevelFixture {
  ViewImage images[2];
  std::vector<float> weights = make_support_weight_table(10.0f);
  LevelInputs in;
  PlaneField fields[2];
  DeviceView device_images[2];
  Buffer<float> device_weights;
  DeviceLevel device_in;

  explicit LevelFixture(const LevelCase& c) {
    const int shift = std::min(3, c.ndisp - 1);
    cv::Mat wide = testing_support::random_rgb8(c.width + shift, c.height, c.seed);
    images[PMS_VIEW_LEFT] = make_view_image(wide(cv::Rect(shift, 0, c.width, c.height)).clone());
    images[PMS_VIEW_RIGHT] = make_view_image(wide(cv::Rect(0, 0, c.width, c.height)).clone());
    for (int view = 0; view < 2; ++view) {
      in.views[view] = &images[view];
      device_images[view] = upload(images[view], view == 0 ? "left" : "right");
      device_in.views[view] = &device_images[view];
    }
    in.weights = weights.data();
    in.cost = {c.window / 2, c.step, 0.9f, 1.0f - 0.9f, 10.0f, 2.0f};
    in.ndisp = c.ndisp;
    in.seed = c.seed;
    in.threads = 2;
    device_weights = guarded(weights, "weights");
    device_in.weights = &device_weights;
    device_in.cost = in.cost;
    device_in.ndisp = in.ndisp;
    device_in.seed = in.seed;
    for (int view = 0; view < 2; ++view) init_random_planes(in, view, 0, fields[view]);
  }
};

}  // namespace flexsight::opencl::test
