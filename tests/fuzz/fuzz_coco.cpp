// A COCO instances file (host/dataset/coco_reader.h): read_coco and the reader's index
// of annotations by image (CocoReader), whose images are not loaded.
#include "host/dataset/coco_reader.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = fuzz::write_file("instances.json", data, size);
  fuzz::expect_input_error_only([&] { flexsight::CocoReader reader(path); });
  return 0;
}
