#pragma once
// The device side of the detect tests and the OpenCL benchmark: one context per
// process (program builds are slow) and the detection stages on it, buffers with a
// guard region of canary bytes after the data, and byte comparisons. The context is
// the device named by $FLEXSIGHT_OPENCL_DEVICE (default: first GPU, else first device),
// as for the stereo tests; without a device, shared_context() throws and the test fails.
// Its own namespace: the stereo fixture's helpers of the same names (guarded_output,
// canary, ...) are other functions, and one test executable links both.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "host/detect/opencl_ssd_stages.h"

namespace flexsight::opencl::ssd_test {

// Elements after every buffer a kernel may write; they must keep the canary.
constexpr size_t kSsdGuard = 64;
constexpr unsigned char kCanaryByte = 0xA5;

inline std::shared_ptr<Context> shared_context() {
  static std::shared_ptr<Context> shared;
  if (!shared) {
    const char* selector = std::getenv("FLEXSIGHT_OPENCL_DEVICE");
    shared = std::make_shared<Context>(select_device(selector ? selector : ""));
  }
  return shared;
}

inline OpenClSsdStages& ssd_stages() {
  static std::unique_ptr<OpenClSsdStages> shared;
  if (!shared) shared = std::make_unique<OpenClSsdStages>(*shared_context());
  return *shared;
}

template <typename T>
T canary() {
  T value;
  std::memset(&value, kCanaryByte, sizeof value);
  return value;
}

// `values` followed by the guard.
template <typename T>
Buffer<T> guarded(std::vector<T> values, const std::string& what) {
  values.resize(values.size() + kSsdGuard, canary<T>());
  return Buffer<T>(*shared_context(), values, what);
}

// `count` canaries and the guard: an element the kernel should write and does not
// shows up as a difference too.
template <typename T>
Buffer<T> guarded_output(size_t count, const std::string& what) {
  return guarded(std::vector<T>(count, canary<T>()), what);
}

// The first `count` elements; fails the test when the guard after them changed.
template <typename T>
std::vector<T> read_checked(const Buffer<T>& buffer, size_t count) {
  std::vector<T> all = buffer.read();
  EXPECT_EQ(all.size(), count + kSsdGuard) << buffer.what();
  if (all.size() != count + kSsdGuard) return {};
  const std::vector<T> guard(kSsdGuard, canary<T>());
  EXPECT_EQ(std::memcmp(all.data() + count, guard.data(), kSsdGuard * sizeof(T)), 0)
      << "a kernel wrote past the end of '" << buffer.what() << "'";
  all.resize(count);
  return all;
}

// The bytes of `value` in hex, in memory order (readable for any T, records included).
template <typename T>
std::string hex_bytes(const T& value) {
  const char* const digits = "0123456789abcdef";
  unsigned char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  std::string text;
  for (unsigned char b : bytes) {
    text += digits[b >> 4];
    text += digits[b & 15];
  }
  return text;
}

// Byte comparison of [first, first + count) of both, the first difference in the message.
template <typename T>
::testing::AssertionResult same_bytes(const std::vector<T>& expected, const std::vector<T>& actual,
                                      size_t first = 0, size_t count = SIZE_MAX) {
  if (expected.size() != actual.size()) {
    return ::testing::AssertionFailure()
           << "sizes differ: " << expected.size() << " vs " << actual.size();
  }
  const size_t end = count == SIZE_MAX ? expected.size() : first + count;
  for (size_t i = first; i < end; ++i) {
    if (std::memcmp(&expected[i], &actual[i], sizeof(T)) != 0) {
      return ::testing::AssertionFailure() << "element " << i << " of " << expected.size()
                                           << " differs: reference " << hex_bytes(expected[i])
                                           << ", OpenCL " << hex_bytes(actual[i]);
    }
  }
  return ::testing::AssertionSuccess();
}

}  // namespace flexsight::opencl::ssd_test
