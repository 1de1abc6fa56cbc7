#include "host/pick/pick_inputs.h"

#include "host/detect/tiled_detection.h"
#include "host/io/calibration.h"
#include "host/io/input_error.h"

namespace flexsight {

PickInputImages read_pick_inputs(const PickInputFiles& files, int detection_tile) {
  PickInputImages images;
  images.pair = load_stereo_pair(files.left, files.right);
  const cv::Mat& left = images.pair.left;
  images.rig = read_stereo_camera(files.calib).resized_to(left.cols, left.rows);
  if (!files.passive_left.empty()) {
    images.passive = load_rgb8(files.passive_left);
    if (images.passive.size() != left.size()) {
      throw InputError(files.passive_left, "is " + std::to_string(images.passive.cols) + "x" +
                                               std::to_string(images.passive.rows) + ", the pair " +
                                               std::to_string(left.cols) + "x" + std::to_string(left.rows) +
                                               ": not the left view without the pattern");
    }
  }
  if (detection_tile > 0) check_tile_fits(detection_tile, left.size(), files.left);
  return images;
}

}  // namespace flexsight
