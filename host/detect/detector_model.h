#pragma once
// A trained detector's folder: the ONNX network M.onnx and, beside it, the files that say
// how to read its outputs (written by scripts/detect/train.py):
//
//   anchors.csv   the anchors, one per output row (ssd_anchors.h)
//   labels.txt    "INDEX CATEGORY_ID NAME" per line: 0 the background, then 1..C, the
//                 class of logit column INDEX and the data set's category id
//   model.json    optional: {"score_function": "softmax" | "sigmoid", "input_size": 300,
//                 "input_range": [-1, 1], "color_order": "rgb", "box_scale": [10, 10, 5, 5]}
//
// model.json exists because the ONNX graph does not say how it was trained: our models
// are trained with softmax cross-entropy, while the TF OD API's are sigmoid (the
// post-processing's default), and reading one with the other's scores gives wrong
// detections without any error. Without the file the defaults are our training's.
#include <string>
#include <vector>

#include "host/detect/ssd_params.h"

namespace flexsight {

// The paths of a model folder's files, from the path of its ONNX file.
struct DetectorFiles {
  std::string model;     // M.onnx
  std::string anchors;   // anchors.csv beside it
  std::string labels;    // labels.txt
  std::string settings;  // model.json (may be absent)
};
DetectorFiles detector_files(const std::string& model_path);

// What model.json says, with the defaults of a model trained by scripts/detect/train.py.
struct DetectorSettings {
  // How the class logits become scores: the training loss's.
  SsdScoreFunction score_function = SsdScoreFunction::Softmax;
  // The network's square input side in pixels.
  int input_size = 300;
  // The box coder's scale factors of the training.
  SsdBoxScale box_scale;
};

// The settings of `path`, or the defaults when it does not exist. Throws InputError
// naming the file for JSON that does not parse, a key of the wrong type or value, and for
// an input_range or color_order other than [-1, 1] and "rgb" (the only preprocessing the
// detector does). Keys it does not know are ignored.
DetectorSettings read_detector_settings(const std::string& path);

// One foreground class of labels.txt.
struct DetectorLabel {
  int category_id = 0;  // the data set's id (COCO "category_id")
  std::string name;
};

// The foreground classes of a labels file, in logit-column order (line INDEX 1 first).
// Throws InputError naming the file and line for a missing or empty file, a line that is
// not "INDEX CATEGORY_ID NAME", indices that do not run 0, 1, 2, ... in order, and a
// category id given to two classes. Blank lines are skipped; line ends may be CRLF.
std::vector<DetectorLabel> read_detector_labels(const std::string& path);

// The model `flexsight detect` uses without --model: the environment variable
// FLEXSIGHT_DETECT_MODEL when set, else the shipped model of this build
// (<source>/models/tless-ssd/model.onnx).
std::string default_detector_model_path();

// Whether default_detector_model_path() comes from FLEXSIGHT_DETECT_MODEL.
bool default_detector_model_from_environment();

// The model a command runs: `given` (its --model) when not empty, else the default, whose
// absence is an InputError of its own (the shipped model missing from the checkout, or
// FLEXSIGHT_DETECT_MODEL naming a file that is not there).
std::string resolve_detector_model_path(const std::string& given);

}  // namespace flexsight
