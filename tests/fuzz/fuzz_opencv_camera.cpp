// OpenCV's stereo calibration output, YAML, XML or JSON (host/geometry/stereo_camera.h
// read_opencv_camera), and read_stereo_camera, which tells the formats apart by content.
#include "host/geometry/stereo_camera.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // The name a user would give it: OpenCV picks the parser by the extension.
  const char* name = size > 0 && data[0] == '<' ? "stereo.xml" : size > 0 && data[0] == '{' ? "stereo.json" : "stereo.yml";
  const std::string path = fuzz::write_file(name, data, size);
  fuzz::expect_input_error_only([&] { flexsight::read_opencv_camera(path); });
  fuzz::expect_input_error_only([&] { flexsight::read_stereo_camera(path); });
  return 0;
}
