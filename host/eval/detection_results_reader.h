#pragma once
// Detections from a results file, in either of the field's two forms, sorted onto the
// images of the ground truth:
//  * COCO results: [{"image_id", "category_id", "bbox": [x, y, w, h], "score"}, ...],
//    image_id the COCO file's image id (what pycocotools' loadRes reads);
//  * BOP 2D detection results: [{"scene_id", "image_id", "category_id", "bbox", "score",
//    "time"}, ...], image_id BOP's im_id and category_id the obj_id.
// The form is the first entry's (a "scene_id" key means BOP); every entry must share it.
#include <string>
#include <vector>

#include "host/eval/detection_ground_truth.h"
#include "host/eval/detection_metrics.h"

namespace flexsight {

struct DetectionResults {
  std::string source;  // the file read
  std::string format;  // "COCO results", "BOP results", or "empty" for []
  // Per image of the ground truth, in its order; each image's boxes in file order.
  std::vector<std::vector<DetectedBox>> per_image;
  // Classes the detector knows that a BOP folder does not name (it names only the objects
  // its scenes show): scored beside the folder's as classes without ground truth.
  std::vector<DetectionCategory> extra_categories;
};

// Reads and checks `path` against `truth`. Throws InputError naming the file and the
// entry index ("entry 7: ...") for anything but a JSON list of such entries: a missing
// key or one of the wrong type, an image the ground truth lacks, a category not among
// its categories, a box that is not 4 finite numbers or has a negative width or height,
// a score that is NaN or outside [0, 1], forms mixed in one file, COCO results for a BOP
// folder (which has no COCO image ids), BOP results for a COCO file without scene_id and
// im_id. NaN and Infinity, which Python's json module writes although JSON has neither,
// are reported as such rather than as a parse error.
DetectionResults read_detection_results(const std::string& path, const DetectionGroundTruth& truth);

}  // namespace flexsight
