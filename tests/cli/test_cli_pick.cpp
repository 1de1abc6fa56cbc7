// `flexsight pick` and `flexsight eval-pick` end to end on one small simulated bin
// (`synth bin`, 960x720, twelve T-LESS parts under the dot projector) with the shipped
// detector and edge templates of all its parts: the whole job runs, its report has every
// key the pick issue asks for with sane values, the parts it ranks are real poses, and
// pick alone gives the same picks as eval-pick.
#include <gtest/gtest.h>
#include <unistd.h>

#include <Eigen/Dense>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "tests/cli/cli_test_support.h"

using namespace flexsight::cli_test_support;
using Json = nlohmann::json;

namespace {

class PickCli : public ::testing::Test {
 protected:
  // ctest runs each test in its own process: each makes its own data (pid in the name).
  static void SetUpTestSuite() {
    root_ = fresh_temp_dir("PickCli_data_" + std::to_string(::getpid()));
    // Fewer views than the default 600: a quarter of the time, still the pose's search.
    RunResult r = run_flexsight(std::string("pose-templates ") + FLEXSIGHT_TLESS_CAD_DIR + " -o " +
                                    (root_ / "parts.tpl").string() + " --views 200 --threads 2",
                                root_);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    r = run_flexsight(std::string("synth bin --count 1 --seed 11 --size 960x720 --parts 12..12 --cad ") +
                          FLEXSIGHT_TLESS_CAD_DIR + " -o " + (root_ / "bins").string(),
                      root_);
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  static void TearDownTestSuite() { fs::remove_all(root_); }
  void SetUp() override { dir_ = fresh_temp_dir(::testing::UnitTest::GetInstance()->current_test_info()->name()); }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir_);
  }
  static std::string common_options() {
    return std::string(" --templates ") + (root_ / "parts.tpl").string() + " --cad " + FLEXSIGHT_TLESS_CAD_DIR +
           " --threads 2 --quiet";
  }
  static Json read_json(const fs::path& path) { return Json::parse(slurp(path)); }

  static fs::path root_;
  fs::path dir_;
};
fs::path PickCli::root_;

// A rotation: orthonormal with determinant +1.
void expect_rotation(const Json& r) {
  ASSERT_EQ(r.size(), 9u);
  Eigen::Matrix3d m;
  for (int i = 0; i < 9; ++i) m(i / 3, i % 3) = r[i].get<double>();
  EXPECT_TRUE((m * m.transpose()).isApprox(Eigen::Matrix3d::Identity(), 1e-4)) << m;
  EXPECT_NEAR(m.determinant(), 1.0, 1e-4);
}

TEST_F(PickCli, EvalPickScoresTheBinAndPickGivesTheSamePicks) {
  const fs::path out = dir_ / "eval";
  RunResult r = run_flexsight("eval-pick " + (root_ / "bins").string() + " --out " + out.string() +
                                  " --pattern-only" + common_options(),
                              dir_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Json report = read_json(out / "report.json");
  EXPECT_EQ(report.at("bins").get<int>(), 1);
  // Parts at least half visible posed within ADD(-S) 0.1 d: 58-70 % on 1280x960 bins
  // (docs/pick.md); on this 0.7 MP bin, with a third of the template views, 4 of 12.
  const double recall = report.at("pose_recall").get<double>();
  EXPECT_GE(recall, 0.2);
  EXPECT_LE(recall, 1.0);
  // The part the robot would take first is posed right.
  EXPECT_EQ(report.at("top1_correct").get<double>(), 1.0);
  EXPECT_LT(report.at("per_bin")[0].at("top1_add_over_diameter").get<double>(), 0.1);
  // The matcher with the active preset on a projector-lit bin: mostly right.
  EXPECT_LT(report.at("bad2_pattern").get<double>(), 25.0);
  EXPECT_TRUE(report.at("bad2_no_pattern").is_null()) << "--pattern-only skips the passive pair";
  EXPECT_GT(report.at("detection_map50").get<double>(), 0.0);
  const Json& stages = report.at("stage_seconds");
  for (const char* stage : {"stereo", "depth", "detection", "pose", "ranking"}) {
    EXPECT_GE(stages.at(stage).get<double>(), 0.0) << stage;
  }
  EXPECT_GT(report.at("seconds_per_bin").get<double>(), stages.at("stereo").get<double>());
  ASSERT_TRUE(fs::exists(out / "report.md"));
  EXPECT_NE(slurp(out / "report.md").find("pose recall"), std::string::npos);
  const cv::Mat picture = cv::imread((out / "bin000.png").string());
  EXPECT_EQ(picture.size(), cv::Size(960, 720));

  // The first pick (pick's default mode), stamped on the way and scored as the top pick.
  const Json& bin_report = report.at("per_bin")[0];
  EXPECT_EQ(report.at("first_pick_correct").get<double>(), bin_report.at("first_pick_correct").get<bool>() ? 1.0 : 0.0);
  EXPECT_TRUE(bin_report.at("seconds_to_first_pick").is_number());
  // It is a candidate the cheap order posed, accepted by the rule when the rule says so.
  const Json bin_picks = read_json(out / "bin000.json");
  const Json& first_pick = bin_picks.at("first_pick");
  const Json& candidates = bin_picks.at("candidates");
  if (first_pick.at("accepted").get<bool>()) {
    const size_t order = first_pick.at("candidate").get<size_t>();
    ASSERT_GE(order, 1u);
    ASSERT_LE(order, candidates.size());
    const Json& chosen = candidates[order - 1];
    EXPECT_TRUE(chosen.at("posed").get<bool>());
    EXPECT_TRUE(chosen.at("accepted").get<bool>());
    EXPECT_EQ(chosen.at("best").at("obj_id"), first_pick.at("obj_id"));
    for (size_t k = 0; k + 1 < order; ++k) {
      EXPECT_FALSE(candidates[k].value("accepted", false)) << "an earlier candidate passed the rule: " << k + 1;
    }
  } else {
    EXPECT_TRUE(first_pick.at("candidate").is_null());
  }

  // pick --all on the same bin, the scene folder as input: the same ranked parts, and
  // the same first pick.
  const fs::path picks_path = dir_ / "picks.json";
  r = run_flexsight("pick " + (root_ / "bins" / "bin000").string() + " --all -o " + picks_path.string() + " --png " +
                        (dir_ / "picks.png").string() + common_options(),
                    dir_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // The same picks, to the bit, but for the time each pose took.
  Json picks = read_json(picks_path).at("picks");
  Json eval_picks = read_json(out / "bin000.json").at("picks");
  ASSERT_FALSE(picks.empty());
  for (Json* list : {&picks, &eval_picks}) {
    for (Json& pick : *list) pick.erase("pose_ms");
  }
  EXPECT_EQ(picks, eval_picks);
  EXPECT_EQ(read_json(picks_path).at("first_pick"), read_json(out / "bin000.json").at("first_pick"));
  EXPECT_EQ(read_json(picks_path).at("mode"), "all");
  double previous_score = 2.0;
  for (size_t i = 0; i < picks.size(); ++i) {
    const Json& pick = picks[i];
    EXPECT_EQ(pick.at("rank").get<size_t>(), i + 1);
    const double score = pick.at("pick_score").get<double>();
    EXPECT_LE(score, previous_score) << "ranked best first";
    previous_score = score;
    const int obj = pick.at("obj_id").get<int>();
    EXPECT_TRUE(obj >= 1 && obj <= 30) << obj;
    const double visible = pick.at("visible_fraction").get<double>();
    EXPECT_TRUE(visible >= 0.0 && visible <= 1.0) << visible;
    expect_rotation(pick.at("R"));
    // The rig looks down on the bin from 1250 mm: every part lies 1000-1500 mm away.
    const double z = pick.at("t_mm")[2].get<double>();
    EXPECT_GT(z, 1000.0);
    EXPECT_LT(z, 1500.0);
  }
  EXPECT_EQ(cv::imread((dir_ / "picks.png").string()).size(), cv::Size(960, 720));
}

// The speed settings of docs/pick.md ("Speed") run the same job: half-size matching and
// the lighter pose still rank real parts.
TEST_F(PickCli, TheSpeedSettingsStillPickParts) {
  const fs::path picks_path = dir_ / "picks.json";
  RunResult r = run_flexsight("pick " + (root_ / "bins" / "bin000").string() + " -o " + picks_path.string() +
                                  " --stereo-downscale 2 --half-turns off --retry-below 0" + common_options(),
                              dir_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Json document = read_json(picks_path);
  ASSERT_FALSE(document.at("picks").empty());
  expect_rotation(document.at("picks")[0].at("R"));
  EXPECT_GT(document.at("seconds").at("stereo").get<double>(), 0.0);
}

// With proposals from depth the bin's floor is found, the regions are listed with whether
// a detector box matched them, and every pose says where its box came from.
TEST_F(PickCli, DepthProposalsListTheRegionsAndMarkEachPicksSource) {
  const fs::path picks_path = dir_ / "picks_depth.json";
  RunResult r = run_flexsight("pick " + (root_ / "bins" / "bin000").string() + " -o " + picks_path.string() +
                                  " --depth-proposals on --stereo-downscale 2 --half-turns off --retry-below 0" +
                                  common_options(),
                              dir_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Json document = read_json(picks_path);
  const Json& depth = document.at("depth_proposals");
  EXPECT_TRUE(depth.at("floor").at("found").get<bool>());
  // The rig looks down from 1250 mm: the floor's normal faces the camera.
  EXPECT_LT(depth.at("floor").at("normal")[2].get<double>(), -0.9);
  ASSERT_FALSE(depth.at("regions").empty());
  int unmatched = 0;
  for (const Json& region : depth.at("regions")) unmatched += !region.at("matched").get<bool>();
  EXPECT_LE(unmatched, depth.at("proposals").get<int>());
  ASSERT_FALSE(document.at("proposals").empty());
  for (const Json& proposal : document.at("proposals")) {
    const std::string source = proposal.at("source").get<std::string>();
    EXPECT_TRUE(source == "network" || source == "depth") << source;
  }
}

}  // namespace
