// The COCO file (host/dataset/coco_writer.h, coco_reader.h): its exact text for a known
// mask, a written data set read back (masks, boxes, areas, ids, file names), and
// malformed files and refused images.
#include <gtest/gtest.h>

#include "host/dataset/coco_reader.h"
#include "host/dataset/dataset_writer.h"
#include "host/dataset/gt_info.h"
#include "tests/dataset/dataset_test_support.h"

using namespace flexsight;
using namespace flexsight::dataset_test_support;

namespace {

// `text` as a coco_instances.json in a fresh folder; returns its path.
std::string coco_file(const ScratchDir& dir, const std::string& text) {
  fs::create_directories(dir / "coco");
  write_file(dir / "coco/coco_instances.json", text);
  return dir / "coco/coco_instances.json";
}

const char* kImages = R"("images": [{"id": 1, "file_name": "a.png", "width": 4, "height": 3}])";

}  // namespace

TEST(CocoFiles, TextOfAKnownMask) {
  ScratchDir dir;
  // Image 3x4 (h x w) with one part whose visible mask is test_coco_rle.cpp's "3230O"
  // mask, drawn as rectangles: pixels (1,0), (1,1), (3,0) and (2,2).
  AnnotatedImage image = rect_image(0, 5, {4, 3}, {{7, {1, 0, 1, 2}, 300}});
  PartAnnotation& part = image.parts[0];
  part.mask_visib.at<uchar>(0, 3) = 255;
  part.mask_visib.at<uchar>(2, 2) = 255;
  DatasetWriter writer(dir / "set", DatasetWriterOptions{});
  writer.add(image, 12);
  writer.finish();
  EXPECT_EQ(file_bytes(dir / "set/coco_instances.json"),
            "{\n"
            "  \"images\": [\n"
            "    {\"id\":12,\"file_name\":\"000000/rgb/000005.jpg\",\"width\":4,\"height\":3,"
            "\"scene_id\":0,\"im_id\":5}\n"
            "  ],\n"
            "  \"annotations\": [\n"
            "    {\"id\":1,\"image_id\":12,\"category_id\":7,\"bbox\":[1.0,0.0,3.0,3.0],"
            "\"area\":4.0,\"segmentation\":{\"size\":[3,4],\"counts\":\"3230O\"},\"iscrowd\":0}\n"
            "  ],\n"
            "  \"categories\": [\n"
            "    {\"id\":7,\"name\":\"obj_07\",\"supercategory\":\"part\"}\n"
            "  ]\n"
            "}\n");
}

TEST(CocoFiles, WrittenDatasetReadsBack) {
  ScratchDir dir;
  std::vector<AnnotatedImage> images = sample_images();
  for (AnnotatedImage& image : images) image.rgb = smooth_rgb(image.rgb.size());
  DatasetWriter writer(dir / "set", DatasetWriterOptions{});
  for (std::size_t i = images.size(); i-- > 0;) writer.add(images[i], 10 * i);
  writer.finish();

  const CocoReader reader(dir / "set/coco_instances.json");
  ASSERT_EQ(reader.size(), images.size());
  std::int64_t next_id = 1;
  for (const CocoAnnotation& annotation : reader.dataset().annotations) {
    EXPECT_EQ(annotation.id, next_id++);  // 1, 2, ... in image order
  }
  ASSERT_EQ(reader.dataset().categories.size(), 3u);
  EXPECT_EQ(reader.dataset().categories[2].name, "obj_03");
  for (std::size_t i = 0; i < images.size(); ++i) {
    SCOPED_TRACE("image " + std::to_string(i));
    const CocoImage& entry = reader.dataset().images[i];
    EXPECT_EQ(entry.id, static_cast<std::int64_t>(10 * i));
    const AnnotatedImage read = reader.load(i);
    EXPECT_EQ(read.scene_id, images[i].scene_id);
    EXPECT_EQ(read.im_id, images[i].im_id);
    EXPECT_GT(cv::PSNR(read.rgb, images[i].rgb), 38.0);
    // One annotation per part with a visible pixel, in gt order.
    std::vector<const PartAnnotation*> visible;
    for (const PartAnnotation& part : images[i].parts) {
      if (part.px_count_visib > 0) visible.push_back(&part);
    }
    ASSERT_EQ(read.parts.size(), visible.size());
    for (std::size_t k = 0; k < visible.size(); ++k) {
      EXPECT_EQ(read.parts[k].obj_id, visible[k]->obj_id);
      EXPECT_EQ(cv::countNonZero(read.parts[k].mask_visib != visible[k]->mask_visib), 0);
      EXPECT_EQ(read.parts[k].bbox_visib, visible[k]->bbox_visib);
      EXPECT_EQ(read.parts[k].px_count_visib, visible[k]->px_count_visib);
    }
  }
  // Image 2's obj 1 is wholly hidden behind obj 2: no annotation.
  EXPECT_EQ(images[2].parts[0].px_count_visib, 0);
  EXPECT_EQ(reader.load(2).parts.size(), 1u);
}

TEST(CocoFiles, PolygonsAreRefused) {
  ScratchDir dir;
  const std::string path = coco_file(
      dir, std::string("{") + kImages +
               R"(, "annotations": [{"id": 1, "image_id": 1, "category_id": 1, "bbox": [0, 0, 1, 1],
         "area": 1, "segmentation": [[0, 0, 1, 0, 1, 1]]}]})");
  EXPECT_TRUE(throws_input_error([&] { read_coco(path); }, path,
                                 "annotations[0]: segmentation is a polygon"));
}

TEST(CocoFiles, RleOfTheWrongSizeOrUnknownImageIsRefused) {
  ScratchDir dir;
  const std::string wrong_sum = coco_file(
      dir, std::string("{") + kImages +
               R"(, "annotations": [{"id": 1, "image_id": 1, "category_id": 1, "bbox": [0, 0, 1, 1],
         "area": 1, "segmentation": {"size": [3, 4], "counts": "3230"}}]})");
  EXPECT_TRUE(throws_input_error([&] { read_coco(wrong_sum); }, wrong_sum,
                                 "RLE counts sum to 10, not size[0] x size[1] = 3 x 4"));
  const std::string wrong_image = coco_file(
      dir, std::string("{") + kImages +
               R"(, "annotations": [{"id": 1, "image_id": 2, "category_id": 1, "bbox": [0, 0, 1, 1],
         "area": 1, "segmentation": {"size": [3, 4], "counts": [12]}}]})");
  EXPECT_TRUE(throws_input_error([&] { read_coco(wrong_image); }, wrong_image,
                                 "image_id 2 is not among the images"));
  const std::string short_bbox = coco_file(
      dir, std::string("{") + kImages +
               R"(, "annotations": [{"id": 1, "image_id": 1, "category_id": 1, "bbox": [0, 0, 1],
         "area": 1, "segmentation": {"size": [3, 4], "counts": [12]}}]})");
  EXPECT_TRUE(throws_input_error([&] { read_coco(short_bbox); }, short_bbox,
                                 "annotations[0]: bbox: expected 4 numbers, found 3"));
}

TEST(CocoFiles, UnknownCategoryAndRepeatedIndexAreRefusedBeforeWriting) {
  ScratchDir dir;
  const std::vector<AnnotatedImage> images = sample_images();
  DatasetWriterOptions options;
  options.categories = {{1, "bracket", "part"}, {2, "cover", "part"}};
  DatasetWriter writer(dir / "set", options);
  writer.add(images[0], 0);
  EXPECT_TRUE(
      throws_input_error([&] { writer.add(images[1], 1); }, "set/coco_instances.json", "obj_id 3"));
  EXPECT_FALSE(fs::exists(dir / "set/000000/rgb/000001.jpg"));
  EXPECT_TRUE(throws_input_error([&] { writer.add(images[2], 0); }, "set/coco_instances.json",
                                 "image index 0 is added twice"));
  EXPECT_FALSE(fs::exists(dir / "set/000000/rgb/000002.jpg"));
}

TEST(CocoFiles, WriterRefusesAFolderInUse) {
  ScratchDir dir;
  fs::create_directories(dir / "set");
  write_file(dir / "set/old.txt", "x");
  EXPECT_TRUE(
      throws_input_error([&] { DatasetWriter writer(dir / "set", {}); }, "set", "is not empty"));
}

TEST(CocoFiles, BoxesOutsideTheImageAreRefused) {
  ScratchDir dir;
  for (const char* bbox : {"[0, 0, -1, 1]", "[3, 0, 1e308, 1]", "[0, 2, 1, 3]"}) {
    const std::string path = coco_file(
        dir, std::string("{") + kImages +
                 R"(, "annotations": [{"id": 1, "image_id": 1, "category_id": 1, "bbox": )" +
                 bbox + R"(, "area": 1, "segmentation": {"size": [3, 4], "counts": [12]}}]})");
    EXPECT_TRUE(throws_input_error([&] { read_coco(path); }, path, "annotations[0]: bbox ["))
        << bbox;
    EXPECT_TRUE(
        throws_input_error([&] { read_coco(path); }, path, "is not a box inside the 4x3 image"))
        << bbox;
  }
}
