// KITTI's 16-bit disparity PNG (host/io/kitti_disparity.h).
#include "host/io/kitti_disparity.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = fuzz::write_file("disp.png", data, size);
  fuzz::expect_input_error_only([&] {
    const cv::Mat disparity = flexsight::read_kitti_disparity(path);
    if (disparity.type() != CV_32FC1) std::abort();
  });
  return 0;
}
