// What the robot is told about each posed part (host/pick/pick_ranking.h): how much of it
// the camera sees, how high it lies, and the order to take the parts.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>

#include "host/pick/pick_ranking.h"
#include "tests/render/render_test_support.h"

using namespace flexsight;
using flexsight::testing_support::box_mesh;

namespace {

Pose at(double x, double y, double z) {
  Pose pose;
  pose.R.setIdentity();
  pose.t = Eigen::Vector3d(x, y, z);
  return pose;
}

// The depth a camera measures of `meshes` at `poses` (0 where nothing is).
cv::Mat measured_depth(const std::vector<std::shared_ptr<const Mesh>>& meshes, const std::vector<Pose>& poses,
                       const PinholeCamera& camera) {
  RenderScene scene;
  for (std::size_t i = 0; i < meshes.size(); ++i) scene.add_instance(scene.add_mesh(meshes[i]), poses[i]);
  scene.commit();
  return raycast(scene, camera).depth;
}

TEST(PickVisibleFraction, AllOfAPartInViewHalfOfOneUnderAPlateNoneOfOneBehindAWall) {
  PinholeCamera camera;  // 640 x 480, f 600
  const auto part = box_mesh(Eigen::Vector3f(20, 20, 10));
  // Alone: every pixel of it is measured at its own depth.
  const Pose pose = at(0, 0, 500);
  EXPECT_DOUBLE_EQ(visible_fraction(part, pose, camera, measured_depth({part}, {pose}, camera), 5.0), 1.0);
  // A plate 100 mm nearer whose left edge is on the optical axis: the right half hidden.
  const auto plate = box_mesh(Eigen::Vector3f(20, 40, 2));
  const cv::Mat covered = measured_depth({part, plate}, {pose, at(20, 0, 400)}, camera);
  EXPECT_NEAR(visible_fraction(part, pose, camera, covered, 5.0), 0.5, 0.06);
  // A wall in front of all of it: nothing seen.
  const auto wall = box_mesh(Eigen::Vector3f(200, 200, 2));
  EXPECT_EQ(visible_fraction(part, pose, camera, measured_depth({part, wall}, {pose, at(0, 0, 300)}, camera), 5.0), 0.0);
  // No measurement at all: unknown pixels count as seen.
  EXPECT_DOUBLE_EQ(visible_fraction(part, pose, camera, cv::Mat::zeros(480, 640, CV_32FC1), 5.0), 1.0);
  // Out of view: no pixel, fraction 0.
  EXPECT_EQ(visible_fraction(part, at(0, 0, -500), camera, covered, 5.0), 0.0);
}

TEST(PickFloorDepth, IsTheFarSurfaceNotTheOutliers) {
  cv::Mat depth(100, 100, CV_32FC1, cv::Scalar(1000));  // the floor
  depth(cv::Rect(10, 10, 30, 30)).setTo(900);           // a part on it
  depth(cv::Rect(0, 0, 100, 2)).setTo(5000);            // 2 % far outliers
  depth(cv::Rect(0, 2, 100, 2)).setTo(0);               // unmeasured
  depth.at<float>(50, 50) = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(floor_depth_mm(depth), 1000.0);
  EXPECT_EQ(floor_depth_mm(cv::Mat::zeros(10, 10, CV_32FC1)), 0.0);
}

TEST(PickRanking, WellPosedUncoveredPartsFirstThenTheHigher) {
  std::vector<PickCandidate> candidates(4);
  const double pose_scores[] = {0.9, 0.9, 0.5, 0.9};
  const double visible[] = {0.5, 1.0, 1.0, 1.0};
  const double heights[] = {80, 20, 90, 60};
  for (int i = 0; i < 4; ++i) {
    candidates[i].obj_id = i;
    candidates[i].pose_score = pose_scores[i];
    candidates[i].visible_fraction = visible[i];
    candidates[i].height_mm = heights[i];
  }
  rank_picks(candidates);
  // 3 and 1 tie at 0.9 (3 lies higher); then 2 (0.5) before 0 (0.9 x 0.5 = 0.45).
  ASSERT_EQ(candidates.size(), 4u);
  EXPECT_EQ(candidates[0].obj_id, 3);
  EXPECT_EQ(candidates[1].obj_id, 1);
  EXPECT_EQ(candidates[2].obj_id, 2);
  EXPECT_EQ(candidates[3].obj_id, 0);
  EXPECT_DOUBLE_EQ(candidates[0].pick_score, 0.9);
  EXPECT_DOUBLE_EQ(candidates[3].pick_score, 0.45);
}

}  // namespace
