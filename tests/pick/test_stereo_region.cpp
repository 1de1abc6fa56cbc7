// The matcher on one rectangle (host/pick/stereo_region.h): the crop arithmetic, and a
// candidate's box refined at full size on a small simulated bin (`synth bin`, 320x240,
// four T-LESS parts under the projector): inside the parts' boxes bad-2 against the ground
// truth falls below the coarse match's, nothing outside a box changes, the same inputs
// give the same bytes, boxes at or past the image's borders work, and pick's depth
// follows the refined disparity.
#include "host/pick/stereo_region.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "host/geometry/depth_from_disparity.h"
#include "host/io/calibration.h"
#include "host/io/image_io.h"
#include "host/io/pfm.h"
#include "host/pick/pick_stereo.h"
#include "tests/cli/cli_test_support.h"

namespace flexsight {
namespace {

using namespace cli_test_support;

TEST(RegionCrop, ReachesTheRangeToTheLeftAndTheMarginAround) {
  const RegionCrop crop = plan_region_crop(cv::Rect(100, 50, 40, 30), {10, 29}, 5, cv::Size(320, 240));
  EXPECT_EQ(crop.shift, 10);
  EXPECT_EQ(crop.ndisp, 20);
  EXPECT_EQ(crop.left, cv::Rect(75, 45, 70, 40));  // 100 - 20 - 5 .. 140 + 5
  EXPECT_EQ(crop.right(), cv::Rect(65, 45, 70, 40));
}

TEST(RegionCrop, StaysInsideTheImageAndAtLeastNdispWide) {
  // At the left edge the crop grows to the right to hold ndisp columns.
  RegionCrop crop = plan_region_crop(cv::Rect(0, 0, 20, 20), {0, 49}, 5, cv::Size(320, 240));
  EXPECT_EQ(crop.left, cv::Rect(0, 0, 50, 25));
  EXPECT_EQ(crop.ndisp, 50);
  // Past the bottom-right corner the box is clipped first.
  crop = plan_region_crop(cv::Rect(300, 220, 40, 40), {5, 14}, 5, cv::Size(320, 240));
  EXPECT_EQ(crop.left, cv::Rect(285, 215, 35, 25));
  // A negative minimum is clamped at 0; a box outside the image gives an empty crop.
  EXPECT_EQ(plan_region_crop(cv::Rect(100, 50, 10, 10), {-4, 9}, 5, cv::Size(320, 240)).shift, 0);
  EXPECT_TRUE(plan_region_crop(cv::Rect(400, 50, 10, 10), {0, 9}, 5, cv::Size(320, 240)).left.empty());
}

TEST(RegionCrop, RangeInABoxSkipsUnknownPixels) {
  cv::Mat d(20, 20, CV_32FC1, cv::Scalar(NAN));
  d.at<float>(5, 5) = 12.4f;
  d.at<float>(6, 7) = 20.2f;
  const DisparityRange range = disparity_range_in(d, cv::Rect(0, 0, 10, 10), 3);
  EXPECT_EQ(range.min, 9);
  EXPECT_EQ(range.max, 24);
  EXPECT_LT(disparity_range_in(d, cv::Rect(10, 10, 10, 10), 3).max, 0);  // nothing known: empty
}

class BoxRefinementOnABin : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(fresh_temp_dir("BoxRefinementOnABin"));
    const RunResult r = run_flexsight("synth bin --count 1 --seed 11 --size 320x240 --parts 4..4 --cad " +
                                          std::string(FLEXSIGHT_TLESS_CAD_DIR) + " -o " + (*dir_ / "bins").string(),
                                      *dir_);
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
  }
  void SetUp() override {
    const fs::path bin = *dir_ / "bins" / "bin000";
    left_ = load_rgb8((bin / "im0.png").string());
    right_ = load_rgb8((bin / "im1.png").string());
    truth_ = read_pfm((bin / "disp0GT.pfm").string());
    apply_stereo_preset("active", params_);
    params_.ndisp = read_middlebury_calib((bin / "calib.txt").string()).ndisp;
    for (const auto& entry : fs::directory_iterator(bin / "mask_visib")) {
      const cv::Mat mask = cv::imread(entry.path().string(), cv::IMREAD_GRAYSCALE) > 0;
      if (cv::countNonZero(mask) < 50) continue;
      masks_.push_back(mask);
      const cv::Rect box = cv::boundingRect(mask);
      boxes_.push_back(cv::Rect(box.x - 4, box.y - 4, box.width + 8, box.height + 8) &
                       cv::Rect(cv::Point(), left_.size()));
    }
    coarse_ = disparity_at_scale(stereo_, left_, right_, params_, 4, {}, nullptr);
  }
  // Of the parts' pixels inside the boxes, the share more than 2 px off the ground truth.
  double bad2_on_parts_in_boxes(const cv::Mat& disparity) const {
    int bad = 0, all = 0;
    for (std::size_t i = 0; i < masks_.size(); ++i) {
      for (int y = boxes_[i].y; y < boxes_[i].br().y; ++y) {
        for (int x = boxes_[i].x; x < boxes_[i].br().x; ++x) {
          if (masks_[i].at<unsigned char>(y, x) == 0 || !std::isfinite(truth_.at<float>(y, x))) continue;
          ++all;
          if (!(std::abs(disparity.at<float>(y, x) - truth_.at<float>(y, x)) <= 2.0f)) ++bad;
        }
      }
    }
    return all > 0 ? static_cast<double>(bad) / all : 1.0;
  }
  static bool same_bytes(const cv::Mat& a, const cv::Mat& b) {
    return a.size() == b.size() && std::equal(a.datastart, a.dataend, b.datastart);
  }

  static fs::path* dir_;
  StereoBackend stereo_{BackendOptions()};
  StereoParams params_;
  cv::Mat left_, right_, truth_, coarse_;
  std::vector<cv::Mat> masks_;
  std::vector<cv::Rect> boxes_;
};
fs::path* BoxRefinementOnABin::dir_ = nullptr;

TEST_F(BoxRefinementOnABin, LowersBad2OnThePartsAndChangesNothingOutsideTheBoxes) {
  ASSERT_GE(boxes_.size(), 2u) << "the bin shows its parts";
  cv::Mat refined = coarse_.clone();
  cv::Mat outside(coarse_.size(), CV_8UC1, cv::Scalar(255));
  for (const cv::Rect& box : boxes_) {
    const RegionCrop crop = refine_disparity_in_box(stereo_, left_, right_, params_, box, refined);
    EXPECT_FALSE(crop.left.empty());
    EXPECT_LT(crop.ndisp, params_.ndisp) << "the box's range, not the pair's";
    outside(box).setTo(0);
  }
  const double coarse = bad2_on_parts_in_boxes(coarse_), fine = bad2_on_parts_in_boxes(refined);
  EXPECT_LT(fine, coarse * 0.8) << "coarse " << coarse << ", refined " << fine;
  cv::Mat changed = (refined != coarse_) & outside;
  EXPECT_EQ(cv::countNonZero(changed), 0);
}

TEST_F(BoxRefinementOnABin, TheSameInputsGiveTheSameBytes) {
  cv::Mat first = coarse_.clone(), second = coarse_.clone();
  refine_disparity_in_box(stereo_, left_, right_, params_, boxes_.at(0), first);
  refine_disparity_in_box(stereo_, left_, right_, params_, boxes_.at(0), second);
  EXPECT_TRUE(same_bytes(first, second));
}

TEST_F(BoxRefinementOnABin, BoxesAtAndPastTheImageBordersWork) {
  for (const cv::Rect& box : {cv::Rect(0, 0, 40, 40), cv::Rect(290, 200, 60, 60), cv::Rect(-20, 100, 50, 30)}) {
    cv::Mat refined = coarse_.clone();
    const RegionCrop crop = refine_disparity_in_box(stereo_, left_, right_, params_, box, refined);
    const cv::Rect inside = box & cv::Rect(cv::Point(), refined.size());
    EXPECT_EQ(crop.left & inside, inside);
    cv::Mat outside(refined.size(), CV_8UC1, cv::Scalar(255));
    outside(inside).setTo(0);
    EXPECT_EQ(cv::countNonZero((refined != coarse_) & outside), 0) << box;
    EXPECT_TRUE(cv::checkRange(refined(inside))) << box;
  }
  cv::Mat untouched = coarse_.clone();
  EXPECT_TRUE(refine_disparity_in_box(stereo_, left_, right_, params_, cv::Rect(400, 0, 10, 10), untouched)
                  .left.empty());
  EXPECT_TRUE(same_bytes(untouched, coarse_));
}

TEST_F(BoxRefinementOnABin, PicksDepthFollowsTheRefinedDisparityInsideTheBoxOnly) {
  const fs::path bin = *dir_ / "bins" / "bin000";
  const StereoCamera rig = read_stereo_camera((bin / "calib.txt").string()).resized_to(left_.cols, left_.rows);
  cv::Mat disparity = coarse_.clone();
  const cv::Mat coarse_depth = depth_from_disparity(coarse_, rig, 1e-3, DepthRule::pick());
  cv::Mat depth = coarse_depth.clone();
  const cv::Rect box = boxes_.at(0);
  refine_pick_box(stereo_, left_, right_, rig, params_, box, 80.0, disparity, depth);
  EXPECT_TRUE(same_bytes(depth, depth_from_disparity(disparity, rig, 1e-3, DepthRule::pick())));
  cv::Mat outside(depth.size(), CV_8UC1, cv::Scalar(255));
  outside(box).setTo(0);
  EXPECT_EQ(cv::countNonZero((depth != coarse_depth) & outside), 0);
  EXPECT_GT(cv::countNonZero(depth(box) != coarse_depth(box)), 0);
}

TEST_F(BoxRefinementOnABin, TheBinsRegionIsMatchedOverItsRangeAndTheRestKeepsTheSearchMatch) {
  const fs::path bin = *dir_ / "bins" / "bin000";
  const StereoCamera rig = read_stereo_camera((bin / "calib.txt").string());
  const BinRegionPlan plan;
  const PickDisparity roi = pick_disparity(stereo_, left_, right_, rig, params_, StereoPlan::kBinRegion, 1);
  StereoParams search_params = params_;
  search_params.coarsest_width = plan.coarsest_width;
  const cv::Mat search = disparity_at_scale(stereo_, left_, right_, search_params,
                                            bin_search_downscale(left_.cols, plan), {}, nullptr);
  ASSERT_EQ(roi.disparity.size(), left_.size());
  EXPECT_TRUE(roi.region.found);
  EXPECT_LT(roi.region.range.count(), params_.ndisp);
  cv::Mat outside(left_.size(), CV_8UC1, cv::Scalar(255));
  outside(roi.region.rect).setTo(0);
  EXPECT_EQ(cv::countNonZero((roi.disparity != search) & outside), 0);
  EXPECT_LT(bad2_on_parts_in_boxes(roi.disparity), bad2_on_parts_in_boxes(search) * 0.8);
}

}  // namespace
}  // namespace flexsight
