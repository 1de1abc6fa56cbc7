#pragma once
// Where the detection data lives (T-LESS CAD models, backgrounds, detector weights) when no
// option names a folder.
#include <string>

namespace flexsight {

// The detection data folder: the environment variable FLEXSIGHT_DETECTION_DATA, else the
// build's default (../shared/detection beside the repository).
std::string detection_data_dir();

// The T-LESS CAD folder of the detection data (detection_data_dir()/cad/tless), where synth,
// pose, pick and eval-pose look for the parts when no --cad is given.
std::string default_cad_dir();

// The background images of the detection data (detection_data_dir()/backgrounds), where
// synth full and synth semi look when no --backgrounds is given.
std::string default_backgrounds_dir();

}  // namespace flexsight
