// The BOP writer and reader together (host/dataset/bop_writer.h, bop_reader.h): what is
// written reads back equal (poses and boxes exactly, masks byte for byte, depth to
// depth_scale), the JSON files' exact layout, the same bytes for any thread count and
// order, and the writer's refusals.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <thread>

#include "host/dataset/bop_reader.h"
#include "host/dataset/bop_writer.h"
#include "tests/dataset/dataset_test_support.h"

using namespace flexsight;
using namespace flexsight::dataset_test_support;

namespace {

BopWriterOptions png_options() {
  BopWriterOptions options;
  options.rgb_format = BopWriterOptions::RgbFormat::png;
  return options;
}

void write_all(const std::string& root, const std::vector<AnnotatedImage>& images,
               const BopWriterOptions& options) {
  BopWriter writer(root, options);
  for (const AnnotatedImage& image : images) writer.write(image);
  writer.finish();
}

bool same_mat(const cv::Mat& a, const cv::Mat& b) {
  if (a.size() != b.size() || a.type() != b.type()) return false;
  return a.empty() || cv::norm(a, b, cv::NORM_INF) == 0;
}

void expect_same_annotations(const AnnotatedImage& read, const AnnotatedImage& written) {
  EXPECT_EQ(read.camera.K, written.camera.K);
  EXPECT_EQ(read.camera.depth_scale, written.camera.depth_scale);
  EXPECT_EQ(read.camera.extra, written.camera.extra);
  ASSERT_EQ(read.parts.size(), written.parts.size());
  for (std::size_t k = 0; k < read.parts.size(); ++k) {
    SCOPED_TRACE("gt " + std::to_string(k));
    const PartAnnotation &a = read.parts[k], &b = written.parts[k];
    EXPECT_EQ(a.obj_id, b.obj_id);
    EXPECT_EQ(a.cam_R_m2c, b.cam_R_m2c);  // doubles are written to read back exactly
    EXPECT_EQ(a.cam_t_m2c, b.cam_t_m2c);
    EXPECT_EQ(a.bbox_obj, b.bbox_obj);
    EXPECT_EQ(a.bbox_visib, b.bbox_visib);
    EXPECT_EQ(a.px_count_all, b.px_count_all);
    EXPECT_EQ(a.px_count_valid, b.px_count_valid);
    EXPECT_EQ(a.px_count_visib, b.px_count_visib);
    EXPECT_EQ(a.visib_fract, b.visib_fract);
  }
}

}  // namespace

TEST(BopRoundTrip, PngWrittenImagesReadBackEqual) {
  ScratchDir dir;
  const std::vector<AnnotatedImage> images = sample_images();
  write_all(dir / "split", images, png_options());

  BopReader reader(dir / "split");
  ASSERT_EQ(reader.size(), images.size());
  for (std::size_t i = 0; i < images.size(); ++i) {
    SCOPED_TRACE("image " + std::to_string(i));
    EXPECT_EQ(reader.ref(i).scene_id, images[i].scene_id);  // sample_images is in order
    EXPECT_EQ(reader.ref(i).im_id, images[i].im_id);
    const AnnotatedImage read = reader.load(i);
    expect_same_annotations(read, images[i]);
    EXPECT_TRUE(same_mat(read.rgb, images[i].rgb));
    // Depth is stored in steps of depth_scale (0.1 mm).
    ASSERT_EQ(read.depth.size(), images[i].depth.size());
    EXPECT_LE(cv::norm(read.depth, images[i].depth, cv::NORM_INF), 0.05 + 1e-4);
    for (std::size_t k = 0; k < read.parts.size(); ++k) {
      EXPECT_TRUE(same_mat(read.parts[k].mask, images[i].parts[k].mask));
      EXPECT_TRUE(same_mat(read.parts[k].mask_visib, images[i].parts[k].mask_visib));
    }
  }
}

TEST(BopRoundTrip, DepthIsRoundedToDepthScaleSteps) {
  ScratchDir dir;
  AnnotatedImage image = rect_image(0, 0, {4, 2}, {});
  image.camera.depth_scale = 0.25;
  image.depth =
      (cv::Mat_<float>(2, 4) << 0.0f, 0.12f, 0.13f, 100.0f, 1000.37f, 16383.0f, 16383.75f, 5.0f);
  write_all(dir / "split", {image}, png_options());
  const cv::Mat read = BopReader(dir / "split").load(0).depth;
  const cv::Mat expected =
      (cv::Mat_<float>(2, 4) << 0.0f, 0.0f, 0.25f, 100.0f, 1000.25f, 16383.0f, 16383.75f, 5.0f);
  EXPECT_EQ(cv::norm(read, expected, cv::NORM_INF), 0.0);
}

TEST(BopRoundTrip, JpgImagesAreCloseAndNamedJpg) {
  ScratchDir dir;
  std::vector<AnnotatedImage> images = sample_images();
  for (AnnotatedImage& image : images) image.rgb = smooth_rgb(image.rgb.size());
  write_all(dir / "split", images, BopWriterOptions{});
  EXPECT_TRUE(fs::exists(dir / "split/000001/rgb/000007.jpg"));
  BopReader reader(dir / "split");
  const AnnotatedImage read = reader.load(1);
  expect_same_annotations(read, images[1]);
  EXPECT_GT(cv::PSNR(read.rgb, images[1].rgb), 38.0);
}

TEST(BopRoundTrip, JsonFilesHaveTheDocumentedLayout) {
  ScratchDir dir;
  AnnotatedImage image = rect_image(3, 10, {6, 4}, {{5, {1, 1, 2, 2}, 400}});
  image.camera.K << 500, 0, 2.5, 0, 500.5, 1.75, 0, 0, 1;
  image.parts[0].cam_R_m2c.setIdentity();
  image.parts[0].cam_t_m2c = Eigen::Vector3d(1.5, -2, 0.1);
  AnnotatedImage second = rect_image(3, 2, {6, 4}, {});
  second.camera = image.camera;
  write_all(dir / "split", {image, second}, png_options());
  // Numeric im_id order ("2" before "10"), sorted keys, shortest round-trip doubles.
  EXPECT_EQ(file_bytes(dir / "split/000003/scene_gt.json"),
            "{\n  \"2\": [],\n  \"10\": [\n"
            "    {\"cam_R_m2c\":[1.0,0.0,0.0,0.0,1.0,0.0,0.0,0.0,1.0],"
            "\"cam_t_m2c\":[1.5,-2.0,0.1],\"obj_id\":5}\n  ]\n}\n");
  EXPECT_EQ(file_bytes(dir / "split/000003/scene_camera.json"),
            "{\n  \"2\": {\"cam_K\":[500.0,0.0,2.5,0.0,500.5,1.75,0.0,0.0,1.0],"
            "\"depth_scale\":0.1},\n"
            "  \"10\": {\"cam_K\":[500.0,0.0,2.5,0.0,500.5,1.75,0.0,0.0,1.0],"
            "\"depth_scale\":0.1}\n}\n");
  EXPECT_EQ(file_bytes(dir / "split/000003/scene_gt_info.json"),
            "{\n  \"2\": [],\n  \"10\": [\n"
            "    {\"bbox_obj\":[1,1,2,2],\"bbox_visib\":[1,1,2,2],\"px_count_all\":4,"
            "\"px_count_valid\":4,\"px_count_visib\":4,\"visib_fract\":1.0}\n  ]\n}\n");
}

TEST(BopRoundTrip, SameBytesForAnyThreadCountAndOrder) {
  ScratchDir dir;
  std::vector<AnnotatedImage> images = sample_images();
  write_all(dir / "serial", images, BopWriterOptions{});

  std::shuffle(images.begin(), images.end(), std::mt19937(7));
  BopWriter writer(dir / "threaded", BopWriterOptions{});
  std::vector<std::thread> threads;
  for (int t = 0; t < 3; ++t) {
    threads.emplace_back([&, t] {
      for (std::size_t i = t; i < images.size(); i += 3) writer.write(images[i]);
    });
  }
  for (std::thread& thread : threads) thread.join();
  writer.finish();
  const auto serial = tree_bytes(dir / "serial"), threaded = tree_bytes(dir / "threaded");
  // 2 scenes x (folder, 4 subfolders, 3 JSON files), 6 x (rgb, depth), 9 parts x 2 masks.
  EXPECT_EQ(serial.size(), 2u * 8u + 12u + 18u);
  EXPECT_TRUE(serial == threaded);
}

TEST(BopRoundTrip, WithoutDepthAndMasksNoneAreWrittenOrRead) {
  ScratchDir dir;
  BopWriterOptions options;
  options.write_depth = false;
  options.write_masks = false;
  std::vector<AnnotatedImage> images = sample_images();
  images[0].depth.release();  // not needed when depth is not written
  write_all(dir / "split", images, options);
  EXPECT_FALSE(fs::exists(dir / "split/000000/depth"));
  EXPECT_FALSE(fs::exists(dir / "split/000000/mask_visib"));
  const AnnotatedImage read = BopReader(dir / "split").load(0);
  EXPECT_TRUE(read.depth.empty());
  EXPECT_TRUE(read.parts.at(0).mask.empty());
  expect_same_annotations(read, images[0]);
}

TEST(BopWriterErrors, DepthBeyondSixteenBitsIsRefusedAndNothingIsWritten) {
  ScratchDir dir;
  AnnotatedImage image = rect_image(0, 3, {5, 4}, {});
  image.depth.at<float>(2, 1) = 6553.6f;  // 65536 steps of 0.1 mm
  BopWriter writer(dir / "split", BopWriterOptions{});
  EXPECT_TRUE(
      throws_input_error([&] { writer.write(image); }, "000000/depth/000003.png", "pixel (1, 2)"));
  EXPECT_FALSE(fs::exists(dir / "split/000000/rgb/000003.jpg"));
  image.depth.at<float>(2, 1) = 6553.5f;  // the largest value that fits
  EXPECT_NO_THROW(writer.write(image));
}

TEST(BopWriterErrors, ImageWrittenTwiceOrWithMissingMaskIsRefused) {
  ScratchDir dir;
  const std::vector<AnnotatedImage> images = sample_images();
  BopWriter writer(dir / "split", BopWriterOptions{});
  writer.write(images[0]);
  EXPECT_TRUE(throws_input_error([&] { writer.write(images[0]); }, "000000/rgb/000000.jpg",
                                 "written twice"));
  AnnotatedImage no_mask = images[1];
  no_mask.parts[0].mask_visib.release();
  EXPECT_TRUE(throws_input_error([&] { writer.write(no_mask); },
                                 "000000/mask_visib/000001_000000.png", "mask is missing"));
  AnnotatedImage bad_extra = images[2];
  bad_extra.camera.extra = {{"cam_K", 1}};
  EXPECT_TRUE(throws_input_error([&] { writer.write(bad_extra); }, "000000/rgb/000002.jpg",
                                 "may not name cam_K"));
}
