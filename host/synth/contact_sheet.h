#pragma once
// A picture of a data set to look at: the first images side by side, each part's
// visible box drawn and labelled with its object id, so a user sees at a glance what a
// generator made (sizes, occlusion, light) and that the boxes sit on the parts.
#include <opencv2/core.hpp>
#include <vector>

#include "host/dataset/annotated_image.h"

namespace flexsight {

struct ContactSheetOptions {
  int columns = 4;
  int tile_width = 240;  // each image scaled to this width, its aspect kept
};

// RGB (CV_8UC3): the images in a grid of `columns`, row-major in the given order, with
// the visible boxes (bbox_visib) of their parts; empty when `images` is.
cv::Mat make_contact_sheet(const std::vector<AnnotatedImage>& images,
                           const ContactSheetOptions& options = {});

}  // namespace flexsight
