#pragma once
// What the OpenCL tests share: the device fixture of device_fixture.h (one context per
// process, guarded buffers, a case's level on both sides) and the byte comparisons that
// check a kernel's output and the guard after it.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "tests/stereo/opencl/device_fixture.h"
#include "tests/common/test_support.h"

namespace flexsight::opencl::test {

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

inline void expect_same_field(const PlaneField& expected, const DeviceField& actual) {
  EXPECT_TRUE(same_buffer(expected.planes, actual.planes)) << "planes";
  EXPECT_TRUE(same_buffer(expected.cost, actual.cost)) << "cost";
}

inline std::string level_case_name(const ::testing::TestParamInfo<LevelCase>& info) {
  return testing_support::case_name(info.param);
}

}  // namespace flexsight::opencl::test
