#pragma once
// What `flexsight detect` writes: the detections of every image in the COCO results
// format (-o), or as a table for a person to read (stdout).
#include <string>
#include <vector>

#include "host/detect/ssd_detector.h"

namespace flexsight {

// One input image's detections.
struct ImageDetections {
  std::string file;  // the path as listed (list_input_images)
  int image_id = 0;  // 1-based position in that list
  int width = 0;
  int height = 0;
  std::vector<ObjectDetection> found;
};

// The COCO results list ("loadRes" format): one object per detection,
//   {"image_id": 1, "category_id": 5, "bbox": [x, y, width, height], "score": 0.98,
//    "file_name": "images/a.png"}
// bbox in pixels of the original image, x and y its top-left corner. Every number is the
// shortest decimal that reads back as the same float, so the text is a function of the
// detections' bytes. One detection per line; "[]" when there are none.
std::string coco_results_text(const std::vector<ImageDetections>& images);

// coco_results_text written to `path` atomically.
void write_coco_results(const std::string& path, const std::vector<ImageDetections>& images);

// Per image a heading line and one row per detection (category id, name, score, box as x,
// y, width, height in pixels).
std::string detection_table(const std::vector<ImageDetections>& images,
                            const std::vector<DetectorLabel>& labels);

}  // namespace flexsight
