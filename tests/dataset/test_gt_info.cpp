// The scene_gt_info numbers (host/dataset/gt_info.h) against masks drawn by hand: a part
// in front, one half hidden behind it, one fully hidden, one partly and one fully
// outside the image, with depth holes on one of them.
#include <gtest/gtest.h>

#include "host/dataset/gt_info.h"
#include "tests/dataset/dataset_test_support.h"

using namespace flexsight;
using namespace flexsight::dataset_test_support;

namespace {

const cv::Size kSize(10, 8);

cv::Mat rect_mask(const cv::Rect& rect) {
  cv::Mat mask(kSize, CV_8UC1, cv::Scalar(0));
  mask(rect & cv::Rect(cv::Point(0, 0), kSize)).setTo(255);
  return mask;
}

PartAnnotation part_of(const cv::Mat& mask, const cv::Mat& mask_visib, const cv::Mat& depth) {
  PartAnnotation part;
  part.mask = mask;
  part.mask_visib = mask_visib;
  fill_gt_info(part, depth);
  return part;
}

void expect_box(const BopBox& box, int x, int y, int w, int h) {
  EXPECT_EQ(box, (BopBox{x, y, w, h}))
      << box.x << " " << box.y << " " << box.width << " " << box.height;
}

// Depth everywhere, but for two holes in the occluded part and one in the background.
cv::Mat depth_with_holes() {
  cv::Mat depth(kSize, CV_32FC1, cv::Scalar(700.0f));
  depth.at<float>(5, 7) = 0.0f;
  depth.at<float>(5, 6) = 0.0f;
  depth.at<float>(0, 0) = 0.0f;
  return depth;
}

}  // namespace

TEST(BopGtInfo, FrontPartIsWhollyVisible) {
  // x 1..4, y 1..5: 20 pixels.
  const cv::Mat a = rect_mask({1, 1, 4, 5});
  const PartAnnotation part = part_of(a, a, depth_with_holes());
  expect_box(part.bbox_obj, 1, 1, 4, 5);
  expect_box(part.bbox_visib, 1, 1, 4, 5);
  EXPECT_EQ(part.px_count_all, 20);
  EXPECT_EQ(part.px_count_valid, 20);
  EXPECT_EQ(part.px_count_visib, 20);
  EXPECT_EQ(part.visib_fract, 1.0);
}

TEST(BopGtInfo, PartHalfHiddenBehindAnother) {
  // B: x 3..7, y 2..5 (20 pixels); the front part covers its columns 3 and 4 (8 pixels),
  // leaving x 5..7, y 2..5 (12 pixels); two of B's pixels have no depth.
  const cv::Mat b = rect_mask({3, 2, 5, 4});
  const cv::Mat b_visible = b & ~rect_mask({1, 1, 4, 5});
  const PartAnnotation part = part_of(b, b_visible, depth_with_holes());
  expect_box(part.bbox_obj, 3, 2, 5, 4);
  expect_box(part.bbox_visib, 5, 2, 3, 4);
  EXPECT_EQ(part.px_count_all, 20);
  EXPECT_EQ(part.px_count_valid, 18);
  EXPECT_EQ(part.px_count_visib, 12);
  EXPECT_DOUBLE_EQ(part.visib_fract, 0.6);
}

TEST(BopGtInfo, FullyHiddenPartKeepsItsBoxAndHasNoVisibleBox) {
  const cv::Mat c = rect_mask({2, 2, 2, 2});
  const PartAnnotation part =
      part_of(c, cv::Mat(kSize, CV_8UC1, cv::Scalar(0)), depth_with_holes());
  expect_box(part.bbox_obj, 2, 2, 2, 2);
  expect_box(part.bbox_visib, -1, -1, -1, -1);
  EXPECT_EQ(part.px_count_all, 4);
  EXPECT_EQ(part.px_count_visib, 0);
  EXPECT_EQ(part.visib_fract, 0.0);
}

TEST(BopGtInfo, PartPartlyOutsideTheImageCountsItsPixelsInside) {
  // The rectangle (8, 6, 5, 5) keeps x 8..9, y 6..7 inside the image: the truncated part
  // is not counted, so it is wholly visible.
  const cv::Mat d = rect_mask({8, 6, 5, 5});
  const PartAnnotation part = part_of(d, d, depth_with_holes());
  expect_box(part.bbox_obj, 8, 6, 2, 2);
  expect_box(part.bbox_visib, 8, 6, 2, 2);
  EXPECT_EQ(part.px_count_all, 4);
  EXPECT_EQ(part.visib_fract, 1.0);
}

TEST(BopGtInfo, PartOutsideTheImageHasNoBoxAndZeroFraction) {
  const cv::Mat none(kSize, CV_8UC1, cv::Scalar(0));
  const PartAnnotation part = part_of(none, none, depth_with_holes());
  expect_box(part.bbox_obj, -1, -1, -1, -1);
  expect_box(part.bbox_visib, -1, -1, -1, -1);
  EXPECT_EQ(part.px_count_all, 0);
  EXPECT_EQ(part.px_count_valid, 0);
  EXPECT_EQ(part.visib_fract, 0.0);
}

TEST(BopGtInfo, WithoutDepthEveryPixelCountsAsMeasured) {
  const cv::Mat b = rect_mask({3, 2, 5, 4});
  EXPECT_EQ(part_of(b, b, cv::Mat()).px_count_valid, 20);
}

TEST(BopGtInfo, MaskBoxOfOnePixelIsOneWide) {
  cv::Mat mask(5, 7, CV_8UC1, cv::Scalar(0));
  mask.at<uchar>(4, 6) = 1;
  expect_box(mask_box(mask), 6, 4, 1, 1);
}

TEST(BopGtInfo, MasksOfTheWrongTypeOrSizeAreInputErrors) {
  PartAnnotation part;
  part.mask = rect_mask({1, 1, 2, 2});
  part.mask_visib = cv::Mat(kSize, CV_16UC1, cv::Scalar(0));
  EXPECT_TRUE(
      throws_input_error([&] { fill_gt_info(part, cv::Mat()); }, "gt_info", "mask_visib is 16U"));
  part.mask_visib = part.mask.clone();
  EXPECT_TRUE(throws_input_error([&] { fill_gt_info(part, cv::Mat(3, 3, CV_32FC1)); }, "gt_info",
                                 "depth is 32F 1-channel 3x3"));
}
