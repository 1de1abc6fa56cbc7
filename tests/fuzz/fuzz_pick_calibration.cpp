// pick's calibration against its pair (host/cli/pick_command.cpp, eval-pick's
// check_bin_inputs): the camera read in any of its formats and fitted to the images' size
// (StereoCamera::resized_to), the rig the pick job derives from it (stereo_rig_from), and
// the disparity range a calib.txt gives. The input is the pair's size (width, height as
// uint16 little-endian, 1..65536), a byte choosing the file's name (calib.txt, .yml,
// .xml: OpenCV tells YAML from XML by the name), then the file's bytes.
#include <cmath>

#include "host/geometry/stereo_camera.h"
#include "host/geometry/stereo_rig.h"
#include "host/io/calibration.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 5) return 0;
  const int width = 1 + (data[0] | (data[1] << 8));
  const int height = 1 + (data[2] | (data[3] << 8));
  static const char* const names[] = {"calib.txt", "calib.yml", "calib.xml"};
  const std::string path = fuzz::write_file(names[data[4] % 3], data + 5, size - 5);
  fuzz::expect_input_error_only([&] {
    const flexsight::StereoCamera camera =
        flexsight::read_stereo_camera(path).resized_to(width, height);
    // A camera that says its size is fitted to the pair's, or refused.
    if (camera.width > 0 && (camera.width != width || camera.height != height)) __builtin_trap();
    const flexsight::StereoRig rig = flexsight::stereo_rig_from(camera, width, height);
    if (rig.left.width != width || rig.left.height != height) __builtin_trap();
    (void)rig.disparity(1000.0);
  });
  fuzz::expect_input_error_only([&] { flexsight::read_middlebury_calib(path); });
  return 0;
}
