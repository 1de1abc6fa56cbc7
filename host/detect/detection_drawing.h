#pragma once
// Pictures of a detector's results to look at (`flexsight detect --png`): each box drawn
// in its class's colour with "CATEGORY_ID SCORE" on it; several images as a grid.
#include <opencv2/core.hpp>
#include <vector>

#include "host/detect/ssd_detector.h"

namespace flexsight {

// `rgb` (CV_8UC3) scaled by `scale` (bilinear below 1) with `found`'s boxes (pixels of
// `rgb`) drawn on it, worst first so that the best boxes stay on top.
cv::Mat draw_detections(const cv::Mat& rgb, const std::vector<ObjectDetection>& found,
                        double scale = 1.0);

struct DetectionSheetOptions {
  int columns = 4;
  int tile_width = 320;  // each image scaled to this width, its aspect kept
};

// The images (RGB) with their detections in a grid of `columns`, row-major, each tile
// labelled with its 1-based position ("#3"); empty when `images` is. `found[i]` belongs
// to `images[i]`.
cv::Mat detection_contact_sheet(const std::vector<cv::Mat>& images,
                                const std::vector<std::vector<ObjectDetection>>& found,
                                const DetectionSheetOptions& options = {});

}  // namespace flexsight
