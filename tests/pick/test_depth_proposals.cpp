// Proposals from depth (host/pick/depth_proposals.h): the depth regions that no detector
// box matches become boxes to pose, named by the detections inside them, else by size.
#include "host/pick/depth_proposals.h"

#include <gtest/gtest.h>

namespace flexsight {
namespace {

ObjectDetection detection(int category, float score, float x, float y, float w, float h) {
  ObjectDetection d;
  d.category_id = category;
  d.class_id = category - 1;
  d.score = score;
  d.box[0] = x;
  d.box[1] = y;
  d.box[2] = x + w;
  d.box[3] = y + h;
  return d;
}

const std::vector<ProposalClass> kClasses = {{1, 0, 60.0}, {2, 1, 120.0}, {3, 2, 170.0}, {4, 3, 100.0}};

std::vector<int> categories(const std::vector<ObjectDetection>& boxes) {
  std::vector<int> ids;
  for (const ObjectDetection& d : boxes) ids.push_back(d.category_id);
  return ids;
}

TEST(DepthProposals, ARegionTakesTheClassesOfTheDetectionsInsideItBestFirst) {
  DepthRegion region;
  region.box = cv::Rect(100, 100, 80, 60);
  region.extent_mm = 110.0;
  const std::vector<ObjectDetection> detections = {
      detection(2, 0.2f, 110, 105, 40, 40),  // inside
      detection(3, 0.5f, 120, 110, 50, 40),  // inside, the best
      detection(2, 0.4f, 105, 100, 60, 50),  // class 2 again, its best score
      detection(4, 0.9f, 170, 150, 60, 60),  // barely overlaps: not lent
      detection(1, 0.1f, 100, 100, 70, 55),  // inside, third
  };
  const std::vector<ObjectDetection> named = region_proposals(region, detections, kClasses, 5);
  EXPECT_EQ(categories(named), (std::vector<int>{3, 2, 1}));
  EXPECT_FLOAT_EQ(named[1].score, 0.4f);
  for (const ObjectDetection& d : named) {
    EXPECT_EQ(d.box[0], 100.0f);
    EXPECT_EQ(d.box[1], 100.0f);
    EXPECT_EQ(d.box[2], 180.0f);
    EXPECT_EQ(d.box[3], 160.0f);
  }
  EXPECT_EQ(categories(region_proposals(region, detections, kClasses, 2)), (std::vector<int>{3, 2}));
}

TEST(DepthProposals, WithoutDetectionsTheClassesOfTheRegionsSizeComeFirst) {
  DepthRegion region;
  region.box = cv::Rect(10, 10, 40, 40);
  region.extent_mm = 110.0;
  const std::vector<ObjectDetection> named = region_proposals(region, {}, kClasses, 3);
  EXPECT_EQ(categories(named), (std::vector<int>{2, 4, 1}));  // 120, 100, then 60 (170 is farther)
  for (const ObjectDetection& d : named) EXPECT_EQ(d.score, 0.0f);
}

TEST(DepthProposals, OnlyRegionsNoDetectionMatchesAreProposed) {
  const PinholeCamera camera = centred_camera(640, 480, 600.0);
  cv::Mat depth(480, 640, CV_32FC1, cv::Scalar(1000.0f));
  depth(cv::Rect(100, 100, 60, 50)).setTo(960.0f);   // a part the detector found
  depth(cv::Rect(300, 200, 80, 60)).setTo(950.0f);   // one it missed
  const std::vector<ObjectDetection> detections = {detection(1, 0.7f, 98, 101, 62, 50)};
  const DepthProposals proposals = propose_from_depth(depth, camera, detections, kClasses, 2);
  ASSERT_EQ(proposals.segmentation.regions.size(), 2u);
  EXPECT_EQ(proposals.matched, (std::vector<bool>{true, false}));
  ASSERT_EQ(proposals.boxes.size(), 2u);  // the missed part, as its two nearest sizes
  EXPECT_EQ(proposals.boxes[0].box[0], 300.0f);
  EXPECT_EQ(proposals.boxes[0].box[3], 260.0f);
  // Its extent: a 100-pixel diagonal at 950 mm, 158 mm: nearest 170, then 120.
  EXPECT_EQ(categories(proposals.boxes), (std::vector<int>{3, 2}));
  const cv::Mat picture = depth_regions_picture(cv::Mat(480, 640, CV_8UC3, cv::Scalar(90, 90, 90)), proposals);
  EXPECT_EQ(picture.size(), depth.size());
  EXPECT_NE(picture.at<cv::Vec3b>(230, 340), cv::Vec3b(90, 90, 90));  // tinted
  EXPECT_EQ(picture.at<cv::Vec3b>(10, 10), cv::Vec3b(90, 90, 90));    // the floor as it was
}

}  // namespace
}  // namespace flexsight
