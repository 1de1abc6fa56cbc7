// BOP's pose errors and matching on cases worked out by hand: a box whose 8 vertices give
// the errors in closed form, a T-LESS part turned about its symmetry axis, and the greedy
// matching of estimates to ground truths with BOP's count of targets.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <iostream>
#include <limits>
#include <memory>

#include "host/eval/pose_errors.h"
#include "host/eval/pose_recall.h"
#include "host/pose/model_symmetries.h"
#include "host/synth/part_library.h"
#include "tests/render/render_test_support.h"

using namespace flexsight;
using flexsight::testing_support::box_mesh;
using flexsight::testing_support::make_pose;

namespace {

// A 60 x 40 x 20 mm box, no symmetry listed (ADD applies), diameter its diagonal.
PoseErrorModel box_model() {
  auto mesh = box_mesh(Eigen::Vector3f(30, 20, 10));
  const double diameter = 2.0 * std::sqrt(30.0 * 30 + 20 * 20 + 10 * 10);
  return PoseErrorModel(mesh, diameter, {SymmetryTransform{}}, false);
}

Eigen::Matrix3d intrinsics(double f, double cx, double cy) {
  Eigen::Matrix3d K;
  K << f, 0, cx, 0, f, cy, 0, 0, 1;
  return K;
}

PinholeCamera camera_of(const Eigen::Matrix3d& K, int width, int height) {
  PinholeCamera camera;
  camera.fx = K(0, 0), camera.fy = K(1, 1), camera.cx = K(0, 2), camera.cy = K(1, 2);
  camera.width = width, camera.height = height;
  return camera;
}

// The part of the T-LESS CAD folder with its symmetries from the repository's table.
struct TlessPart {
  std::unique_ptr<PoseErrorModel> model;
  ModelInfo info;
};

TlessPart tless_part(int obj_id) {
  const PartLibrary parts = PartLibrary::load_folder(FLEXSIGHT_TLESS_CAD_DIR);
  const auto table = read_models_info(std::string(FLEXSIGHT_SOURCE_DIR) + "/models/tless-cad/models_info.json");
  TlessPart part;
  part.info = table.at(obj_id);
  part.model = std::make_unique<PoseErrorModel>(parts.part(parts.index_of(obj_id)).mesh, part.info.diameter,
                                                symmetry_transformations(part.info), part.info.symmetric());
  return part;
}

const Pose kTruth = make_pose(35, Eigen::Vector3d(1, 2, 0.5), Eigen::Vector3d(12, -8, 400));

}  // namespace

TEST(PoseErrors, IdenticalPosesGiveZeroForEveryError) {
  const PoseErrorModel box = box_model();
  const Eigen::Matrix3d K = intrinsics(500, 159.5, 119.5);
  // Zero up to rounding: ADD-S and MSSD take the vertices through R^T R.
  EXPECT_EQ(add_error(box, kTruth, kTruth), 0.0);
  EXPECT_NEAR(adds_error(box, kTruth, kTruth), 0.0, 1e-9);
  EXPECT_NEAR(mssd_error(box, kTruth, kTruth), 0.0, 1e-9);
  EXPECT_EQ(mspd_error(box, kTruth, kTruth, K), 0.0);
  // VSD: the test depth is the part's own, alone.
  ModelDepthRenderer renderer(box.shared_mesh());
  const cv::Mat depth = renderer.depth(kTruth, camera_of(K, 320, 240));
  ASSERT_GT(cv::countNonZero(depth), 1000);
  for (double e : vsd_errors(depth, depth, depth, K, box.diameter())) EXPECT_EQ(e, 0.0);
  // A symmetric T-LESS part too, with its hundreds of symmetry transformations.
  const TlessPart part = tless_part(4);
  EXPECT_NEAR(adds_error(*part.model, kTruth, kTruth), 0.0, 1e-9);
  EXPECT_NEAR(mssd_error(*part.model, kTruth, kTruth), 0.0, 1e-9);
  EXPECT_NEAR(mspd_error(*part.model, kTruth, kTruth, K), 0.0, 1e-9);
}

// A shift by s along the camera's x axis moves every vertex by s: ADD = MSSD = s; a
// vertex at depth z moves by fx s / z pixels, so MSPD = fx s / (the least depth).
TEST(PoseErrors, KnownTranslationGivesKnownErrors) {
  const PoseErrorModel box = box_model();
  const Eigen::Matrix3d K = intrinsics(500, 159.5, 119.5);
  Pose shifted = kTruth;
  shifted.t.x() += 7.5;
  EXPECT_NEAR(add_error(box, shifted, kTruth), 7.5, 1e-9);
  EXPECT_NEAR(mssd_error(box, shifted, kTruth), 7.5, 1e-9);
  double least_depth = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& x : box.points()) least_depth = std::min(least_depth, (kTruth.R * x + kTruth.t).z());
  EXPECT_NEAR(mspd_error(box, shifted, kTruth, K), 500 * 7.5 / least_depth, 1e-9);
  // ADD-S: each true vertex to the nearest shifted one; the box's edges are all longer
  // than 15 mm, so that is its own shifted copy.
  EXPECT_NEAR(adds_error(box, shifted, kTruth), 7.5, 1e-9);
  EXPECT_EQ(add_or_adds_error(box, shifted, kTruth), add_error(box, shifted, kTruth));
}

// The box 0.32 d farther along the optical axis: behind the test surface by more than
// delta, yet visible where the truth is (BOP's rule for the estimate), and every pixel
// of the overlap off by 0.32 d to 0.3225 d (the rays' slant). VSD is 1 up to tau = 0.3;
// above, only the share of the truth's silhouette that the smaller, farther box leaves
// uncovered counts.
TEST(PoseErrors, VsdOfADepthShift) {
  const PoseErrorModel box = box_model();
  const Eigen::Matrix3d K = intrinsics(500, 159.5, 119.5);
  const PinholeCamera camera = camera_of(K, 320, 240);
  const Pose truth = make_pose(0, Eigen::Vector3d::UnitZ(), Eigen::Vector3d(0, 0, 300));
  Pose farther = truth;
  farther.t.z() += 0.32 * box.diameter();
  ModelDepthRenderer renderer(box.shared_mesh());
  const cv::Mat depth_truth = renderer.depth(truth, camera);
  const cv::Mat depth_farther = renderer.depth(farther, camera);
  const double uncovered = 1.0 - static_cast<double>(cv::countNonZero(depth_farther)) / cv::countNonZero(depth_truth);
  const std::vector<double> e = vsd_errors(depth_truth, depth_farther, depth_truth, K, box.diameter());
  const std::vector<double> taus = VsdSettings{}.taus;
  ASSERT_EQ(e.size(), 10u);
  for (std::size_t k = 0; k < taus.size(); ++k) {
    if (taus[k] <= 0.3) {
      EXPECT_EQ(e[k], 1.0) << taus[k];
    } else {
      EXPECT_NEAR(e[k], uncovered, 1e-12) << taus[k];
    }
  }
  EXPECT_GT(uncovered, 0.1);
  EXPECT_LT(uncovered, 0.9);
}

// obj_04 has a continuous symmetry about z: turned by 77 degrees about it (not a
// multiple of the discretisation step, 360 / 315 degrees), the estimate is right by ADD-S and MSSD and far
// wrong by ADD.
TEST(PoseErrors, SymmetricPartTurnedAboutItsAxisIsRightUnderAddSAndMssdOnly) {
  const TlessPart part = tless_part(4);
  ASSERT_EQ(part.info.symmetries_continuous.size(), 1u);
  const Eigen::Vector3d axis = part.info.symmetries_continuous[0].axis;
  const double d = part.model->diameter();
  Pose turned = kTruth;
  turned.R = kTruth.R * Eigen::AngleAxisd(77.0 * M_PI / 180.0, axis).toRotationMatrix();
  const double add = add_error(*part.model, turned, kTruth);
  const double adds = adds_error(*part.model, turned, kTruth);
  const double mssd = mssd_error(*part.model, turned, kTruth);
  EXPECT_GT(add, 0.1 * d);
  EXPECT_LT(adds, 0.1 * d);
  EXPECT_LT(mssd, 0.05 * d);  // right at BOP's tightest MSSD threshold
  EXPECT_EQ(add_or_adds_error(*part.model, turned, kTruth), adds);
  std::cout << "obj_04 turned 77 deg: ADD " << add / d << " d, ADD-S " << adds / d << " d, MSSD " << mssd / d
            << " d\n";
  // obj_05's discrete symmetry (a half turn about z): MSSD exactly 0.
  const TlessPart part5 = tless_part(5);
  ASSERT_EQ(part5.info.symmetries_discrete.size(), 1u);
  const SymmetryTransform& s = part5.info.symmetries_discrete[0];
  Pose flipped = kTruth;
  flipped.R = kTruth.R * s.R;
  flipped.t = kTruth.R * s.t + kTruth.t;
  EXPECT_NEAR(mssd_error(*part5.model, flipped, kTruth), 0.0, 1e-9);
  EXPECT_GT(add_error(*part5.model, flipped, kTruth), 0.1 * part5.model->diameter());
  EXPECT_LT(adds_error(*part5.model, flipped, kTruth), 0.1 * part5.model->diameter());
}

TEST(PoseErrors, MatchingTakesEstimatesBestScoreFirstAndTheSmallestError) {
  // One ground truth, two estimates: the better-scored one is wrong, the other right.
  EXPECT_EQ(match_poses({0.9, 0.5}, {{5.0}, {1.0}}, {true}, 3.0), std::vector<int>({1}));
  // Both right: the better-scored one takes it, whatever the errors.
  EXPECT_EQ(match_poses({0.5, 0.9}, {{1.0}, {2.0}}, {true}, 3.0), std::vector<int>({1}));
  // Two ground truths: the best estimate takes its nearer one, the next the other.
  EXPECT_EQ(match_poses({0.9, 0.8}, {{2.0, 1.0}, {1.5, 0.5}}, {true, true}, 3.0), std::vector<int>({1, 0}));
  // Strictly below the threshold; invalid ground truths never match.
  EXPECT_EQ(match_poses({0.9}, {{3.0}}, {true}, 3.0), std::vector<int>({-1}));
  EXPECT_EQ(match_poses({0.9}, {{1.0, 2.0}}, {false, true}, 3.0), std::vector<int>({-1, 0}));
  // Equal scores keep the given order (Python's stable sort).
  EXPECT_EQ(match_poses({0.7, 0.7}, {{2.0}, {1.0}}, {true}, 3.0), std::vector<int>({0}));
}

// Through the accumulator: BOP counts only the best-scored estimates, as many as the
// object has targets in the image, so a wrong best estimate for a lone target is a miss
// even when a worse-scored one is right; a target without estimate is a miss; a ground
// truth below min_visib_fract is no target.
TEST(PoseErrors, RecallCountsTargetsAndMissesAsBopDoes) {
  const PoseErrorModel box = box_model();
  const std::map<int, const PoseErrorModel*> models = {{1, &box}};
  const double d = box.diameter();
  const Pose a = make_pose(10, Eigen::Vector3d::UnitX(), Eigen::Vector3d(-40, 0, 500));
  const Pose b = make_pose(20, Eigen::Vector3d::UnitY(), Eigen::Vector3d(40, 0, 500));
  const Pose c = make_pose(30, Eigen::Vector3d::UnitZ(), Eigen::Vector3d(0, 40, 500));
  Pose a_far = a;
  a_far.t.x() += 0.22 * d;  // wrong by ADD at 0.1 d, right by MSSD from 0.25 d on
  PoseEvalImage image;
  image.K = intrinsics(500, 159.5, 119.5);
  image.width = 320, image.height = 240;
  image.truth = {{1, a, 0.9}, {1, b, 0.6}, {1, c, 0.05}};
  // Two targets (c is 5 % visible): a wrong estimate scored best, a right one for a, a
  // right one for c; none for b. Kept: the best two, a_far and a: one match.
  image.estimates = {{1, a_far, 0.9}, {1, a, 0.8}, {1, c, 0.7}};
  PoseRecallAccumulator accumulator(models);
  accumulator.add_image(image);
  const PoseScores& s = accumulator.total();
  EXPECT_EQ(s.ground_truth, 3);
  EXPECT_EQ(s.targets, 2);
  EXPECT_EQ(s.targets_visib50, 2);
  EXPECT_EQ(s.estimates, 3);
  EXPECT_EQ(s.estimates_matched_against_targets, 2);
  EXPECT_DOUBLE_EQ(s.add_recall(), 0.5);
  // At every MSSD threshold one of a_far and a takes a, and nothing comes near b.
  EXPECT_DOUBLE_EQ(s.ar_mssd(), 0.5);
  EXPECT_FALSE(s.has_vsd);             // no depth given
  EXPECT_DOUBLE_EQ(s.ar(), (s.ar_mssd() + s.ar_mspd()) / 2);
  ASSERT_EQ(accumulator.per_object().count(1), 1u);
  EXPECT_DOUBLE_EQ(accumulator.per_object().at(1).add_recall(), 0.5);

  // The right estimate alone: a found, b (no estimate) a miss.
  image.estimates = {{1, a, 0.8}};
  PoseRecallAccumulator second(models);
  second.add_image(image);
  EXPECT_DOUBLE_EQ(second.total().add_recall(), 0.5);
  EXPECT_DOUBLE_EQ(second.total().ar_mssd(), 0.5);
  // Both right: 1.
  image.estimates = {{1, b, 0.3}, {1, a, 0.8}};
  PoseRecallAccumulator third(models);
  third.add_image(image);
  EXPECT_DOUBLE_EQ(third.total().add_recall(), 1.0);
  EXPECT_DOUBLE_EQ(third.total().ar(), 1.0);
  // A least visibility of 0.7 leaves a (0.9) the only target, and a single estimate,
  // the best-scored one, to match it.
  PoseEvalSettings strict;
  strict.min_visib_fract = 0.7;
  PoseRecallAccumulator fourth(models, strict);
  fourth.add_image(image);
  EXPECT_EQ(fourth.total().targets, 1);
  EXPECT_EQ(fourth.total().estimates_matched_against_targets, 1);  // the best: a
  EXPECT_DOUBLE_EQ(fourth.total().add_recall(), 1.0);
}

// BOP's MSPD thresholds (5..50 px) hold at 640 pixels of width: the same error of 8 px
// passes the 5 px threshold in an image 1280 wide and fails it at 640.
TEST(PoseErrors, MspdThresholdsScaleWithTheImageWidth) {
  const PoseErrorModel box = box_model();
  const std::map<int, const PoseErrorModel*> models = {{1, &box}};
  const Pose truth = make_pose(0, Eigen::Vector3d::UnitZ(), Eigen::Vector3d(0, 0, 500));
  const Eigen::Matrix3d K = intrinsics(500, 320, 240);
  double least_depth = 500 - 10;  // the box's near face
  Pose shifted = truth;
  shifted.t.x() = 8.0 * least_depth / 500;  // 8 px at the near face
  ASSERT_NEAR(mspd_error(box, shifted, truth, K), 8.0, 1e-9);
  for (int width : {640, 1280}) {
    PoseEvalImage image;
    image.K = K;
    image.width = width, image.height = 480;
    image.truth = {{1, truth, 1.0}};
    image.estimates = {{1, shifted, 1.0}};
    PoseRecallAccumulator accumulator(models);
    accumulator.add_image(image);
    const std::vector<double> recalls = accumulator.total().mspd.recalls();
    EXPECT_EQ(recalls[0], width == 1280 ? 1.0 : 0.0) << width;  // the 5 px threshold
    EXPECT_EQ(recalls[1], 1.0) << width;                         // 10 px
  }
}
