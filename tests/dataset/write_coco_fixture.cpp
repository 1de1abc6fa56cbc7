// flexsight_write_coco_fixture OUT: writes a small data set with known masks into the new
// folder OUT, for coco_pycocotools_check.py: the masks whose RLE strings
// test_coco_rle.cpp works out by hand, then tests/dataset/rect_images.h's sample images
// (overlaps, a hidden part, a part cut by the border).
#include <iostream>

#include "host/dataset/dataset_writer.h"
#include "host/io/input_error.h"
#include "tests/dataset/rect_images.h"

using namespace flexsight;
using namespace flexsight::dataset_test_support;

namespace {

// A one-pixel-wide image whose single part is set on the rows in [first, last) pairs.
AnnotatedImage column_image(int im_id, int height, std::vector<std::pair<int, int>> set_rows) {
  AnnotatedImage image =
      rect_image(0, im_id, {1, height},
                 {{4, {0, set_rows[0].first, 1, set_rows[0].second - set_rows[0].first}, 300}});
  PartAnnotation& part = image.parts[0];
  for (const auto& [first, last] : set_rows) part.mask_visib.rowRange(first, last).setTo(255);
  part.mask = part.mask_visib.clone();
  fill_gt_info(part, image.depth);
  return image;
}

std::vector<AnnotatedImage> fixture_images() {
  std::vector<AnnotatedImage> images;
  // 3x4: columns 000, 110, 001, 100 -> "3230O".
  AnnotatedImage small = rect_image(0, 0, {4, 3}, {{7, {1, 0, 1, 2}, 300}});
  small.parts[0].mask_visib.at<uchar>(0, 3) = 255;
  small.parts[0].mask_visib.at<uchar>(2, 2) = 255;
  small.parts[0].mask = small.parts[0].mask_visib.clone();
  fill_gt_info(small.parts[0], small.depth);
  images.push_back(small);
  images.push_back(column_image(1, 40, {{35, 40}}));         // "S15"
  images.push_back(column_image(2, 50, {{44, 50}}));         // "\16"
  images.push_back(column_image(3, 11, {{1, 6}, {9, 11}}));  // "153M"
  for (AnnotatedImage image : sample_images()) {
    image.scene_id += 1;  // apart from the column images' scene 0
    images.push_back(image);
  }
  return images;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: flexsight_write_coco_fixture OUT_FOLDER\n";
    return 2;
  }
  try {
    DatasetWriterOptions options;
    options.bop.rgb_format = BopWriterOptions::RgbFormat::png;
    DatasetWriter writer(argv[1], options);
    const std::vector<AnnotatedImage> images = fixture_images();
    for (std::size_t i = 0; i < images.size(); ++i) writer.add(images[i], static_cast<int>(i));
    writer.finish();
  } catch (const InputError& e) {
    std::cerr << e.what() << "\n";
    return 1;
  }
  return 0;
}
