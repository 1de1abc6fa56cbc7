// The semi-synthetic generator: a patch lands where, as large and as turned as asked;
// the images are a function of (seed, index); every part keeps the visible fraction
// the cap asks; boxes and masks follow the pasted pixels.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>
#include <thread>

#include "host/io/input_error.h"
#include "host/synth/patch_paste.h"
#include "host/synth/semi_synthetic.h"
#include "tests/render/render_test_support.h"
#include "tests/synth/synth_test_support.h"

using namespace flexsight;
using namespace flexsight::testing_support;

namespace {

// A patch shaped like an L (a bar 21 wide and 5 high, and a leg down its left end),
// mid-grey; its mask is not symmetric, so a mirror or a turn shows.
Patch l_patch(int obj_id = 3) {
  Patch patch;
  patch.obj_id = obj_id;
  patch.source = "L";
  patch.rgb = cv::Mat(11, 21, CV_8UC3, cv::Scalar(120, 120, 120));
  patch.mask = cv::Mat::zeros(11, 21, CV_8UC1);
  patch.mask(cv::Rect(0, 0, 21, 5)).setTo(255);
  patch.mask(cv::Rect(0, 0, 5, 11)).setTo(255);
  return patch;
}

PatchPlacement at(double x, double y) {
  PatchPlacement placement;
  placement.centre = {x, y};
  return placement;
}

}  // namespace

TEST(SemiSyntheticPaste, PatchLandsCentredAtScale) {
  const cv::Size size(100, 80);
  PatchPlacement placement = at(50, 40);
  const PlacedPatch same = place_patch(l_patch(), placement, size);
  // Unscaled and unturned: the mask itself, its centre pixel (10, 5) on (50, 40).
  EXPECT_EQ(mask_box(same.mask), (BopBox{40, 35, 21, 11}));
  EXPECT_EQ(cv::countNonZero(same.mask), cv::countNonZero(l_patch().mask));
  placement.scale = 2.0;
  const PlacedPatch twice = place_patch(l_patch(), placement, size);
  const BopBox box = mask_box(twice.mask);
  EXPECT_NEAR(box.width, 42, 1);
  EXPECT_NEAR(box.height, 22, 1);
  EXPECT_NEAR(box.x + (box.width - 1) / 2.0, 50, 1);
  // Area four times the patch's, give or take the rim: a pixel on the mask's edge is
  // in when more than half covered, which at a scale of exactly 2 drops one tied rim.
  EXPECT_NEAR(cv::countNonZero(twice.mask), 4 * cv::countNonZero(l_patch().mask), 70);
}

TEST(SemiSyntheticPaste, TurnAndMirrorMoveTheMaskAsExpected) {
  const cv::Size size(100, 80);
  PatchPlacement placement = at(50, 40);
  placement.angle_degrees = 90;  // counter-clockwise: the bar stands up on the left
  const PlacedPatch turned = place_patch(l_patch(), placement, size);
  cv::Mat expected;
  cv::rotate(place_patch(l_patch(), at(50, 40), size).mask(cv::Rect(40, 35, 21, 11)), expected,
             cv::ROTATE_90_COUNTERCLOCKWISE);
  EXPECT_EQ(mask_box(turned.mask), (BopBox{45, 30, 11, 21}));
  EXPECT_EQ(cv::countNonZero(turned.mask(cv::Rect(45, 30, 11, 21)) != expected), 0);

  placement = at(50, 40);
  placement.mirror = true;
  const PlacedPatch mirrored = place_patch(l_patch(), placement, size);
  cv::Mat flipped;
  cv::flip(l_patch().mask, flipped, 1);
  EXPECT_EQ(cv::countNonZero(mirrored.mask(cv::Rect(40, 35, 21, 11)) != flipped), 0);
}

TEST(SemiSyntheticPaste, BrightnessContrastAndSoftEdgeStayInsideTheMask) {
  cv::Mat image(80, 100, CV_8UC3, cv::Scalar(0, 200, 0));
  PatchPlacement placement = at(50, 40);
  placement.gain = 0.5;
  placement.offset = 10;
  const PlacedPatch placed = place_patch(l_patch(), placement, image.size());
  paste_patch(image, placed);
  // Inside the bar, away from its edge: 0.5 * (120 - 128) + 128 + 10 = 134.
  EXPECT_EQ(image.at<cv::Vec3b>(37, 50), cv::Vec3b(134, 134, 134));
  // Outside the mask nothing changes (the edge is softened inwards only).
  cv::Mat outside = placed.mask == 0;
  cv::Mat changed;
  cv::inRange(image, cv::Scalar(0, 200, 0), cv::Scalar(0, 200, 0), changed);
  EXPECT_EQ(cv::countNonZero(outside & ~changed), 0);
}

TEST(SemiSynthetic, SameBytesFromAnyThreadAndVisibleFractionsHold) {
  std::vector<Patch> patches = {l_patch(3), l_patch(7)};
  patches[1].rgb.setTo(cv::Scalar(40, 60, 200));
  SemiSyntheticSettings settings;
  settings.width = 120;
  settings.height = 90;
  settings.min_parts = 4;
  settings.max_parts = 6;
  const BackgroundLibrary& backgrounds = real_backgrounds();
  std::vector<AnnotatedImage> first(6), second(6);
  std::thread forward([&] {
    for (int i = 0; i < 6; ++i) first[i] = render_semi_synthetic(settings, patches, backgrounds, 5, i);
  });
  std::thread backward([&] {
    for (int i = 5; i >= 0; --i) second[i] = render_semi_synthetic(settings, patches, backgrounds, 5, i);
  });
  forward.join();
  backward.join();
  for (int i = 0; i < 6; ++i) {
    EXPECT_TRUE(same_mat_bytes(first[i].rgb, second[i].rgb)) << i;
    ASSERT_EQ(first[i].parts.size(), second[i].parts.size());
    ASSERT_FALSE(first[i].parts.empty());
    for (size_t p = 0; p < first[i].parts.size(); ++p) {
      const PartAnnotation& part = first[i].parts[p];
      EXPECT_TRUE(same_mat_bytes(part.mask_visib, second[i].parts[p].mask_visib));
      EXPECT_TRUE(part.obj_id == 3 || part.obj_id == 7);
      EXPECT_GE(part.visib_fract, settings.min_visible_fraction);
      EXPECT_EQ(part.bbox_visib, mask_box(part.mask_visib));
      EXPECT_EQ(part.bbox_obj, mask_box(part.mask));
      EXPECT_EQ(cv::countNonZero(part.mask_visib & ~part.mask), 0);
      // A later paste hides an earlier one: no two visible masks overlap.
      for (size_t q = p + 1; q < first[i].parts.size(); ++q) {
        EXPECT_EQ(cv::countNonZero(part.mask_visib & first[i].parts[q].mask_visib), 0);
      }
    }
  }
  EXPECT_FALSE(same_mat_bytes(first[0].rgb, first[1].rgb));
}

TEST(SemiSynthetic, KnownOccluderGivesTheExpectedVisibleFraction) {
  // Two solid squares of 20x20, the second pasted over the right half of the first:
  // the first keeps exactly half its pixels.
  Patch square;
  square.obj_id = 1;
  square.rgb = cv::Mat(20, 20, CV_8UC3, cv::Scalar(90, 90, 90));
  square.mask = cv::Mat(20, 20, CV_8UC1, cv::Scalar(255));
  const cv::Size size(60, 40);
  const PlacedPatch below = place_patch(square, at(19.5, 19.5), size);
  const PlacedPatch above = place_patch(square, at(29.5, 19.5), size);
  PartAnnotation part;
  part.mask = below.mask;
  part.mask_visib = below.mask & ~above.mask;
  fill_gt_info(part, cv::Mat());
  EXPECT_EQ(part.px_count_all, 400);
  EXPECT_EQ(part.px_count_visib, 200);
  EXPECT_DOUBLE_EQ(part.visib_fract, 0.5);
  EXPECT_EQ(part.bbox_visib, (BopBox{10, 10, 10, 20}));
}

TEST(SemiSynthetic, SettingsErrorsNameTheOption) {
  SemiSyntheticSettings settings;
  settings.min_parts = 0;
  EXPECT_THROW(settings.check(), InputError);
  settings = {};
  settings.min_contrast = 2.0;
  try {
    settings.check();
    ADD_FAILURE() << "no error";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("--min-contrast"), std::string::npos) << error.what();
  }
}
