#pragma once
// The detect tests' comparison of two detection lists: same length, and every detection
// the same bytes (class, score, box, anchor), the first difference in the message.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "host/detect/detection.h"

namespace flexsight::testing_support {

inline ::testing::AssertionResult same_detections(const std::vector<Detection>& expected,
                                                  const std::vector<Detection>& actual) {
  if (expected.size() != actual.size()) {
    return ::testing::AssertionFailure()
           << expected.size() << " detections expected, " << actual.size() << " found";
  }
  for (size_t i = 0; i < expected.size(); ++i) {
    const Detection& e = expected[i];
    const Detection& a = actual[i];
    if (std::memcmp(&e, &a, sizeof(Detection)) != 0) {
      return ::testing::AssertionFailure()
             << "detection " << i << ": expected class " << e.class_id << " anchor " << e.anchor
             << " score " << e.score << " box " << e.box[0] << "," << e.box[1] << ","
             << e.box[2] << "," << e.box[3] << "; got class " << a.class_id << " anchor "
             << a.anchor << " score " << a.score << " box " << a.box[0] << "," << a.box[1]
             << "," << a.box[2] << "," << a.box[3];
    }
  }
  return ::testing::AssertionSuccess();
}

}  // namespace flexsight::testing_support
