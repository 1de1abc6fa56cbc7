// Middlebury v2 ground truth and region masks, 8-bit PNG (host/io/middlebury_v2.h).
#include "host/io/middlebury_v2.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = fuzz::write_file("disp.png", data, size);
  fuzz::expect_input_error_only([&] {
    const cv::Mat disparity = flexsight::read_middlebury_v2_disparity(path, 4.0);
    if (disparity.type() != CV_32FC1) std::abort();
  });
  fuzz::expect_input_error_only([&] {
    const cv::Mat mask = flexsight::read_mask(path);
    if (mask.type() != CV_8UC1) std::abort();
  });
  return 0;
}
