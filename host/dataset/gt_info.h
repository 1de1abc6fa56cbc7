#pragma once
// The numbers of BOP's scene_gt_info.json (boxes, pixel counts, visible fraction) from a
// part's masks and the image's depth: one definition for the generators, which fill
// their annotations with it, and the tests, which check them against it.
#include <opencv2/core.hpp>

#include "host/dataset/annotated_image.h"

namespace flexsight {

// The box of the non-zero pixels of a CV_8UC1 mask: x, y of the top-left one, width and
// height counting pixels (x_max - x_min + 1). (-1, -1, -1, -1) when none is set.
BopBox mask_box(const cv::Mat& mask);

// Fills part.bbox_obj, bbox_visib, px_count_all, px_count_valid, px_count_visib and
// visib_fract from part.mask (amodal), part.mask_visib (both CV_8UC1, non-zero on the
// part, the image's size) and `depth` (CV_32FC1 in mm, 0 where nothing was measured; an
// empty Mat counts every pixel as measured, as a renderer's depth has no gaps):
//   px_count_all   = pixels of mask (the part inside the image; what lies outside the
//                    image is not counted, so visib_fract ignores truncation),
//   px_count_valid = pixels of mask where depth > 0,
//   px_count_visib = pixels of mask_visib,
//   visib_fract    = px_count_visib / px_count_all, 0 when px_count_all is 0,
//   bbox_obj       = mask_box(mask), bbox_visib = mask_box(mask_visib).
// A part hidden behind others keeps its bbox_obj and gets bbox_visib (-1, -1, -1, -1);
// one outside the image gets both. Throws InputError ("gt_info: ...") for masks or depth
// of the wrong type or size.
void fill_gt_info(PartAnnotation& part, const cv::Mat& depth);

}  // namespace flexsight
