// D2CO's Levenberg-Marquardt refinement (host/pose/dcd_refiner.h) on a rendered T-LESS
// part: from poses 10 degrees and 10 mm off, the edge points of the template seen from
// the nearest viewpoint are pulled back onto the image's edges, and the pose with them.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <iostream>
#include <random>

#include "host/pose/dcd_refiner.h"
#include "host/pose/edge_template.h"
#include "host/pose/pose_math.h"
#include "host/render/mesh.h"
#include "host/render/raycaster.h"
#include "tests/pose/pose_test_support.h"

using namespace flexsight;
using flexsight::pose_test_support::picture;

namespace {


TEST(DcdRefiner, ConvergesFromPosesTenDegreesAndTenMillimetresOff) {
  auto mesh = std::make_shared<const Mesh>(load_mesh(std::string(FLEXSIGHT_TLESS_CAD_DIR) + "/obj_21.stl"));
  TemplateParams template_params;
  template_params.views = 300;
  const PartTemplates part = make_part_templates(*mesh, 21, "obj_21", template_params, 2);

  PinholeCamera camera;  // 640 x 480, f 600
  Pose truth;
  truth.R = (Eigen::AngleAxisd(0.6, Eigen::Vector3d(1, 2, 0.5).normalized())).toRotationMatrix();
  truth.t = Eigen::Vector3d(15.0, -10.0, 450.0);
  RenderScene scene;
  scene.add_instance(scene.add_mesh(mesh), truth);
  scene.commit();
  const cv::Mat image = picture(raycast(scene, camera));
  DcdParams dcd;
  const DcdTensor tensor(detect_edges(image, cv::Rect(0, 0, 640, 480), dcd), dcd);

  // The view whose camera direction is nearest the true one (the in-plane turn does not
  // change which points are visible).
  const Eigen::Vector3d direction = -(truth.R.transpose() * truth.t).normalized();
  int nearest = 0;
  for (int v = 0; v < static_cast<int>(part.views.size()); ++v) {
    const Eigen::Vector3d d = part.views[v].rotation.row(2).transpose();
    if (-d.dot(direction) > -Eigen::Vector3d(part.views[nearest].rotation.row(2).transpose()).dot(direction)) nearest = v;
  }
  const EdgeView& view = part.views[nearest];
  const double at_truth = mean_chamfer(view.points, view.tangents, truth, camera, tensor, {0, 0});
  EXPECT_LT(at_truth, 2.0);  // measured 1.58: the view's points are not exactly the true pose's

  std::mt19937 random(7);
  std::normal_distribution<double> normal;
  int converged_trials = 0;
  for (int trial = 0; trial < 6; ++trial) {
    const Eigen::Vector3d axis = Eigen::Vector3d(normal(random), normal(random), normal(random)).normalized();
    const Eigen::Vector3d shift = Eigen::Vector3d(normal(random), normal(random), normal(random)).normalized();
    Pose start;
    start.R = rotation_from_axis_angle(axis * (10.0 * M_PI / 180.0)) * truth.R;
    start.t = truth.t + 10.0 * shift;
    const DcdRefineResult result = refine_on_dcd(view.points, view.tangents, start, camera, tensor, {0, 0}, {});
    const double turn = rotation_angle_degrees(result.pose.R, truth.R);
    const double across = (result.pose.t - truth.t).head<2>().norm();
    const double along = std::abs(result.pose.t.z() - truth.t.z());
    // Edges fix the position across the image tightly, the distance less so (a size
    // change of a fraction of a pixel).
    const bool converged = turn < 2.0 && across < 1.5 && along < 6.0 && result.final_cost < at_truth + 0.5;
    std::cout << "trial " << trial << ": " << turn << " deg, " << across << " mm across, " << along
              << " mm along, cost " << result.initial_cost << " -> " << result.final_cost << "\n";
    converged_trials += converged;
  }
  // Measured: 5 of 6 (one start falls into a neighbouring minimum of the edge fit, 23
  // degrees off; the search's several candidates and ICP exist for that case).
  EXPECT_GE(converged_trials, 5);
}

}  // namespace
