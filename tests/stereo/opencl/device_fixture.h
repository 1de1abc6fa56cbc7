#pragma once
// The device side of tests/stereo/kernel_cases.h, shared by the OpenCL tests and the OpenCL
// benchmark: one device context per process (program builds are slow), buffers with a
// canary-filled guard region after the data, and a case's level uploaded to the device.
// No GoogleTest here (opencl_test_support.h adds the comparisons).
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "host/stereo/opencl_stages.h"
#include "tests/stereo/kernel_cases.h"

namespace flexsight::opencl::test {

using testing_support::advance;
using testing_support::DisparityPair;
using testing_support::LevelCase;
using testing_support::level_cases;
using testing_support::median_inputs;
using testing_support::MedianInputs;
using testing_support::random_confidence;
using testing_support::random_consistency;
using testing_support::random_disparities;
using testing_support::ReferenceLevel;
using testing_support::search_schedule;

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

inline DeviceView upload(const ViewImage& image, const std::string& what) {
  return {image.width, image.height, guarded(image.color, what + " colour"),
          guarded(image.gradient, what + " gradient")};
}

inline DeviceField upload(const PlaneField& field, const std::string& what) {
  return {field.width, field.height, guarded(field.planes, what + " planes"),
          guarded(field.cost, what + " cost")};
}

// A case's ReferenceLevel with its images and weight table on the device as well.
struct LevelFixture : ReferenceLevel {
  DeviceView device_images[2];
  Buffer<float> device_match[2];
  Buffer<float> device_weights;
  DeviceLevel device_in;

  explicit LevelFixture(const LevelCase& c, int threads = 2) : ReferenceLevel(c, threads) {
    for (int view = 0; view < 2; ++view) {
      device_images[view] = upload(images[view], view == 0 ? "left" : "right");
      device_in.views[view] = &device_images[view];
      device_match[view] = guarded_output<float>(
          match_record_floats(device_images[view].pixels()),
          view == 0 ? "left match records" : "right match records");
      stages().pack_match_samples(device_images[view], device_match[view]);
      device_in.match[view] = &device_match[view];
    }
    device_weights = guarded(weights, "weights");
    device_in.weights = &device_weights;
    device_in.cost = in.cost;
    device_in.ndisp = in.ndisp;
    device_in.seed = in.seed;
  }
};

}  // namespace flexsight::opencl::test
