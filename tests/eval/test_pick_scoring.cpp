// eval-pick's scoring of one bin (host/eval/pick_scoring.h) on a bin `synth bin` renders:
// picks at the ground-truth poses are all right, picks moved by 0.2 d are all wrong, the
// ground-truth disparity has bad-2 0 and a disparity 3 px off has bad-2 100 %, and the
// detection truth is the parts in view.
#include "host/eval/pick_scoring.h"

#include <gtest/gtest.h>

#include <set>

#include "host/dataset/bop_reader.h"
#include "host/io/pfm.h"
#include "tests/cli/cli_test_support.h"

namespace flexsight {
namespace {

using namespace cli_test_support;

class PickScoring : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(fresh_temp_dir("PickScoring"));
    const RunResult r = run_flexsight("synth bin --count 1 --seed 5 --size 480x360 --parts 4..4 --cad " +
                                          std::string(FLEXSIGHT_TLESS_CAD_DIR) + " -o " + (*dir_ / "bins").string(),
                                      *dir_);
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
  }
  static std::string bin() { return (*dir_ / "bins" / "bin000").string(); }
  static fs::path* dir_;
};
fs::path* PickScoring::dir_ = nullptr;

// A PickResult whose picks are the bin's ground-truth parts, each moved along x by
// `shift_diameters` of its diameter, ranked in file order.
PickResult picks_at_truth(const BopReader& reader, const PoseScoringModels& models, double shift_diameters) {
  PickResult result;
  result.disparity = read_pfm((fs::path(reader.scene_dir(0)) / "disp0GT.pfm").string());
  for (const PartAnnotation& part : reader.record(0).parts) {
    PickCandidate c;
    c.obj_id = part.obj_id;
    c.pose.R = part.cam_R_m2c;
    c.pose.t = part.cam_t_m2c + Eigen::Vector3d(shift_diameters * models.models.at(part.obj_id)->diameter(), 0, 0);
    c.pick_score = 1.0 - 0.01 * static_cast<double>(result.picks.size());
    result.picks.push_back(c);
  }
  return result;
}

TEST_F(PickScoring, PicksAtTheTruthAreRightAndMovedOnesWrong) {
  const BopReader reader(bin());
  const std::set<int> ids = bin_obj_ids({bin()});
  ASSERT_FALSE(ids.empty());
  std::map<int, std::string> source_of;
  for (int id : ids) source_of[id] = bin();
  const std::string cad = FLEXSIGHT_TLESS_CAD_DIR;
  const std::string info = default_models_info_beside(cad);
  const PoseScoringModels models = load_pose_scoring_models(ids, cad, info, source_of);

  int half_visible = 0, in_view = 0;
  for (const PartAnnotation& part : reader.record(0).parts) {
    half_visible += part.visib_fract >= 0.5 ? 1 : 0;
    in_view += part.px_count_visib > 0 ? 1 : 0;
  }
  ASSERT_GT(half_visible, 0);

  const PickResult right = picks_at_truth(reader, models, 0.0);
  const cv::Mat truth = right.disparity;
  const BinPickScore good = score_pick_on_bin(bin(), right, truth + 3.0f, models, cad, info);
  EXPECT_EQ(good.targets_visib50, half_visible);
  EXPECT_EQ(good.posed_visib50, half_visible);
  EXPECT_TRUE(good.top1_correct);
  EXPECT_NEAR(good.top1_error_ratio, 0.0, 1e-9);
  EXPECT_EQ(good.bad2_pattern, 0.0);
  EXPECT_EQ(good.bad2_no_pattern, 100.0);
  EXPECT_EQ(good.parts, in_view);
  EXPECT_EQ(static_cast<int>(good.truth_boxes.size()), in_view);

  // Moved by more than a diameter: every model point at least 0.5 d from every point of
  // the part where it was (ADD-S, the nearest-point distance of symmetric parts, can be
  // far below a smaller shift: a cylinder moved along its axis).
  const BinPickScore moved = score_pick_on_bin(bin(), picks_at_truth(reader, models, 1.5), cv::Mat(), models, cad, info);
  EXPECT_EQ(moved.posed_visib50, 0);
  EXPECT_FALSE(moved.top1_correct);
  EXPECT_GE(moved.top1_error_ratio, 0.5);
  EXPECT_LE(moved.top1_error_ratio, 1.5 + 1e-9);
  EXPECT_TRUE(std::isnan(moved.bad2_no_pattern));  // not run
}

}  // namespace
}  // namespace flexsight
