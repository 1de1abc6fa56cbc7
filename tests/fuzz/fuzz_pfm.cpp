// read_pfm (host/io/pfm.h) on arbitrary bytes.
#include "host/io/pfm.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = fuzz::write_file("input.pfm", data, size);
  fuzz::expect_input_error_only([&] {
    const cv::Mat image = flexsight::read_pfm(path);
    // What the header promised is what came back.
    if (image.empty() || (image.type() != CV_32FC1 && image.type() != CV_32FC3)) std::abort();
  });
  return 0;
}
