#pragma once
// Boxes, pixel counts and visible fraction of a part from its masks and the depth image,
// as BOP's scene_gt_info.json defines them. The synthetic generator's own copy, kept in
// this one function so that host/dataset's shared helper can replace it.
#include <opencv2/core.hpp>

#include "host/dataset/annotated_image.h"

namespace flexsight {

// Sets part.bbox_obj (box of `amodal`), bbox_visib (box of `visible`), px_count_all
// (pixels of `amodal`), px_count_valid (of those, pixels where `depth` > 0),
// px_count_visib (pixels of `visible`) and visib_fract (px_count_visib / px_count_all,
// 0 when the part has no pixel). Masks CV_8UC1 (non-zero: on the part), depth CV_32FC1,
// all of the image's size; an empty `depth` counts no valid pixel.
void annotate_from_masks(const cv::Mat& amodal, const cv::Mat& visible, const cv::Mat& depth,
                         PartAnnotation& part);

}  // namespace flexsight
