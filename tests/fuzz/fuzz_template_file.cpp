// The pose estimator's template file (host/pose/template_file.h read_template_set).
#include "host/pose/template_file.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = fuzz::write_file("templates.bin", data, size);
  fuzz::expect_input_error_only([&] { flexsight::read_template_set(path); });
  return 0;
}
