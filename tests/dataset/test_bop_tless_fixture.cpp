// The real T-LESS / BOP layout read unchanged: tests/data/bop_tless_like is a scene as
// the BOP toolkit writes it (T-LESS's extra camera keys, depth_scale 0.1, PNG rgb, a gray
// image, mask_visib/ only, the toolkit's boxes; see make_fixture.py there).
#include <gtest/gtest.h>

#include "host/dataset/bop_reader.h"
#include "host/dataset/bop_writer.h"
#include "tests/dataset/dataset_test_support.h"

using namespace flexsight;
using namespace flexsight::dataset_test_support;

namespace {

std::string fixture() { return std::string(FLEXSIGHT_TEST_DATA_DIR) + "/bop_tless_like"; }

}  // namespace

TEST(BopTlessFixture, SplitAndSceneFolderListTheSameImages) {
  const BopReader split(fixture());
  const BopReader scene(fixture() + "/000001");
  ASSERT_EQ(split.size(), 2u);
  ASSERT_EQ(scene.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(split.ref(i).scene_id, 1);
    EXPECT_EQ(scene.ref(i).scene_id, 1);
    EXPECT_EQ(split.ref(i).im_id, static_cast<int>(i));
  }
}

TEST(BopTlessFixture, CameraKeepsTlessExtraKeys) {
  const AnnotatedImage image = BopReader(fixture()).load(0);
  Eigen::Matrix3d K;
  K << 1075.65091572, 0.0, 374.06888344, 0.0, 1073.90347929, 255.72159802, 0.0, 0.0, 1.0;
  EXPECT_EQ(image.camera.K, K);
  EXPECT_EQ(image.camera.depth_scale, 0.1);
  EXPECT_EQ(image.camera.extra.at("elev"), 30);
  EXPECT_EQ(image.camera.extra.at("mode"), 0);
  EXPECT_EQ(image.camera.extra.at("cam_R_w2c").size(), 9u);
  EXPECT_EQ(image.camera.extra.at("cam_t_w2c")[2], 650.0);
  EXPECT_FALSE(image.camera.extra.contains("cam_K"));
}

TEST(BopTlessFixture, ImagesDepthAndVisibleMasksAreRead) {
  const AnnotatedImage image = BopReader(fixture()).load(0);
  ASSERT_EQ(image.rgb.type(), CV_8UC3);
  ASSERT_EQ(image.rgb.size(), cv::Size(32, 24));
  // make_fixture.py: rgb = (7x, 9y, 3(x + y)), in RGB order.
  EXPECT_EQ(image.rgb.at<cv::Vec3b>(2, 5), cv::Vec3b(35, 18, 21));
  ASSERT_EQ(image.depth.type(), CV_32FC1);
  EXPECT_FLOAT_EQ(image.depth.at<float>(5, 5), 600.0f);    // part 0 at 6000 * 0.1 mm
  EXPECT_FLOAT_EQ(image.depth.at<float>(20, 30), 900.0f);  // background
  EXPECT_EQ(image.depth.at<float>(0, 0), 0.0f);            // a hole
  ASSERT_EQ(image.parts.size(), 2u);
  EXPECT_TRUE(image.parts[0].mask.empty());  // T-LESS test scenes ship mask_visib only here
  EXPECT_EQ(cv::countNonZero(image.parts[0].mask_visib), 80);
  EXPECT_EQ(cv::countNonZero(image.parts[1].mask_visib), 148);
  EXPECT_EQ(image.parts[1].mask_visib.at<uchar>(18, 22), 255);
}

TEST(BopTlessFixture, PosesAndGtInfoAreKeptAsWritten) {
  const AnnotatedImage image = BopReader(fixture()).load(0);
  const PartAnnotation& part = image.parts[1];
  EXPECT_EQ(part.obj_id, 25);
  EXPECT_EQ(part.cam_t_m2c, Eigen::Vector3d(-7.0, -5.5, 700.0));
  Eigen::Matrix3d R;
  R << 0, 1, 0, 1, 0, 0, 0, 0, -1;
  EXPECT_EQ(part.cam_R_m2c, R);
  // The BOP toolkit's box (width = x_max - x_min), not recomputed.
  EXPECT_EQ(part.bbox_obj, (BopBox{9, 7, 13, 11}));
  EXPECT_EQ(part.px_count_all, 168);
  EXPECT_EQ(part.px_count_visib, 148);
  EXPECT_EQ(part.visib_fract, 0.8809523809523809);
}

TEST(BopTlessFixture, GrayImageBecomesThreeEqualChannels) {
  const AnnotatedImage image = BopReader(fixture()).load(1);
  ASSERT_EQ(image.rgb.type(), CV_8UC3);
  cv::Mat channels[3];
  cv::split(image.rgb, channels);
  EXPECT_EQ(cv::countNonZero(channels[0] != channels[1]), 0);
  EXPECT_EQ(cv::countNonZero(channels[0] != channels[2]), 0);
  EXPECT_GT(cv::countNonZero(channels[0]), 0);
}

TEST(BopTlessFixture, WrittenAgainKeepsTheExtraCameraKeys) {
  ScratchDir dir;
  const BopReader reader(fixture());
  BopWriterOptions options;
  options.rgb_format = BopWriterOptions::RgbFormat::png;
  options.write_masks = false;  // the fixture has no amodal masks
  BopWriter writer(dir / "copy", options);
  for (std::size_t i = 0; i < reader.size(); ++i) writer.write(reader.load(i));
  writer.finish();
  const AnnotatedImage again = BopReader(dir / "copy").load(0);
  const AnnotatedImage original = reader.load(0);
  EXPECT_EQ(again.camera.extra, original.camera.extra);
  EXPECT_EQ(again.parts[1].bbox_obj, original.parts[1].bbox_obj);
  EXPECT_EQ(cv::norm(again.depth, original.depth, cv::NORM_INF), 0.0);
  EXPECT_NE(file_bytes(dir / "copy/000001/scene_camera.json").find("\"elev\":30"),
            std::string::npos);
}
