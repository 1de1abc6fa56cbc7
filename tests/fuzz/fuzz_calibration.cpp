// The stereo benchmarks' calibration files (host/io/calibration.h): Middlebury 2014
// calib.txt and KITTI calib, each reader on the same bytes, and the camera built from
// them (host/geometry/stereo_camera.h read_middlebury_camera / read_kitti_camera).
#include "host/geometry/stereo_camera.h"
#include "host/io/calibration.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = fuzz::write_file("calib.txt", data, size);
  fuzz::expect_input_error_only([&] { flexsight::read_middlebury_calib(path); });
  fuzz::expect_input_error_only([&] { flexsight::read_kitti_calib(path); });
  fuzz::expect_input_error_only([&] { flexsight::read_middlebury_camera(path); });
  fuzz::expect_input_error_only([&] { flexsight::read_kitti_camera(path); });
  return 0;
}
