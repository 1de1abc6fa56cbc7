// `flexsight pose-templates` and `flexsight pose DATASET --gt-boxes` end to end on a small
// rendered BOP data set of two real T-LESS parts, one part per image, depth with the
// stereo noise model (synth full --depth-noise): the poses, scored by `flexsight
// eval-pose`, are mostly right; and bad input is a clear error, exit code 1, nothing
// written.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "host/dataset/bop_pose_results.h"
#include "host/io/input_error.h"
#include "host/pose/template_file.h"
#include "tests/cli/cli_test_support.h"

using namespace flexsight;
using namespace flexsight::cli_test_support;

namespace {

class PoseCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = fresh_temp_dir("PoseCli_data");
    // Two parts: obj_05 (symmetric by a half turn) and obj_21 (no symmetry).
    fs::create_directories(root_ / "cad");
    for (const char* name : {"obj_05.stl", "obj_21.stl"}) {
      fs::copy_file(fs::path(FLEXSIGHT_TLESS_CAD_DIR) / name, root_ / "cad" / name);
    }
    RunResult r = run_flexsight("pose-templates " + (root_ / "cad").string() + " -o " +
                                    (root_ / "parts.tpl").string() + " --views 300 --threads 2",
                                root_);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    r = run_flexsight("synth full --count 8 --size 320x240 --min-parts 1 --max-parts 1 --seed 5"
                      " --min-size 0.3 --max-size 0.5 --depth-noise 0.25 --rgb png --cad " +
                          (root_ / "cad").string() + " --backgrounds " + FLEXSIGHT_BACKGROUNDS_DIR +
                          " --hflip 0 --vflip 0 --max-rotation 0 --threads 2 -o " + (root_ / "data").string(),
                      root_);
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  static void TearDownTestSuite() { fs::remove_all(root_); }
  void SetUp() override {
    dir_ = fresh_temp_dir(::testing::UnitTest::GetInstance()->current_test_info()->name());
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir_);
  }
  std::string pose_command(const std::string& extra) const {
    return "pose " + (root_ / "data").string() + " --gt-boxes --templates " + (root_ / "parts.tpl").string() +
           " --cad " + (root_ / "cad").string() + " " + extra;
  }

  static fs::path root_;
  fs::path dir_;
};
fs::path PoseCli::root_;

TEST_F(PoseCli, TemplateFileHoldsEveryPartOfTheFolder) {
  const TemplateSet set = read_template_set((root_ / "parts.tpl").string());
  ASSERT_EQ(set.parts.size(), 2u);
  EXPECT_EQ(set.parts[0].obj_id, 5);
  EXPECT_EQ(set.parts[1].obj_id, 21);
  for (const auto& part : set.parts) {
    ASSERT_EQ(part.views.size(), 300u);
    for (const auto& view : part.views) {
      EXPECT_GT(view.points.size(), 20u);
      EXPECT_EQ(view.points.size(), view.tangents.size());
      // Edge points lie on the part: within its diameter of the model's origin.
      for (const auto& p : view.points) EXPECT_LT(p.norm(), part.diameter);
      EXPECT_LT(view.surface_depth_offset, 0.0f);  // the visible surface is nearer than the centre
    }
  }
}

TEST_F(PoseCli, PosesMostIsolatedPartsWithinAddS) {
  const fs::path out = dir_ / "poses";
  RunResult r = run_flexsight(pose_command("--out " + out.string()), dir_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* name : {"poses.csv", "report.md", "poses.jpg"}) EXPECT_TRUE(fs::exists(out / name)) << name;
  const auto records = read_bop_pose_results((out / "poses.csv").string());
  EXPECT_EQ(records.size(), 8u);
  const fs::path eval = dir_ / "eval";
  r = run_flexsight("eval-pose " + (root_ / "data").string() + " --results " + (out / "poses.csv").string() +
                        " --cad " + (root_ / "cad").string() + " --out " + eval.string() + " --quiet",
                    dir_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream in(eval / "report.json");
  const auto report = nlohmann::json::parse(in);
  // Measured: ADD(-S) recall 0.375 (3 of 8), VSD AR 0.71: the outlines fit, but obj_21,
  // listed without symmetry, is near-symmetric about its axis and is often posed turned
  // about it (docs/pose.md). Floors that random or unrefined poses fall far below.
  EXPECT_GE(report["add_recall"].get<double>(), 0.25) << report.dump(1);
  EXPECT_GE(report["ar_vsd"].get<double>(), 0.6) << report.dump(1);
}

TEST_F(PoseCli, BadInputIsAnErrorAndWritesNothing) {
  const fs::path out = dir_ / "out";
  const std::string tpl = (root_ / "parts.tpl").string();
  // A template file that is not one, and a truncated one.
  const fs::path junk = dir_ / "junk.tpl";
  std::ofstream(junk) << "not templates";
  const fs::path cut = dir_ / "cut.tpl";
  {
    const std::string bytes = slurp(tpl);
    std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  }
  // A CAD folder without obj_21.
  fs::create_directories(dir_ / "cad_without_21");
  fs::copy_file(root_ / "cad" / "obj_05.stl", dir_ / "cad_without_21" / "obj_05.stl");
  const std::string data = (root_ / "data").string();
  struct Case {
    std::string arguments, expected;
  };
  const std::vector<Case> cases = {
      {"pose " + data + " --templates " + tpl + " --out " + out.string(), "--gt-boxes"},
      {"pose " + data + " --gt-boxes --out " + out.string(), "--templates"},
      {"pose " + data + " --gt-boxes --templates " + tpl, "--out"},
      {"pose " + data + " --gt-boxes --templates " + junk.string() + " --out " + out.string(), "not a template file"},
      {"pose " + data + " --gt-boxes --templates " + cut.string() + " --out " + out.string(), "truncated"},
      {"pose " + data + " --gt-boxes --templates " + tpl + " --cad " + (dir_ / "cad_without_21").string() +
           " --out " + out.string(),
       "no CAD model of object 21"},
      {pose_command("--out " + out.string() + " --min-visib 2"), "--min-visib"},
      {pose_command("--out " + out.string() + " --refinement maybe"), "--refinement"},
      {pose_command("--out " + out.string() + " --limit 0"), "--limit"},
      {"pose-templates " + (root_ / "cad").string(), "-o"},
      {"pose-templates " + (dir_ / "nowhere").string() + " -o " + (dir_ / "t.tpl").string(), "nowhere"},
      {"pose-templates " + (root_ / "cad").string() + " -o " + (dir_ / "t.tpl").string() + " --views 0", "--views"},
  };
  for (const Case& c : cases) {
    const RunResult r = run_flexsight(c.arguments, dir_);
    EXPECT_EQ(r.exit_code, 1) << c.arguments << "\n" << r.err;
    EXPECT_NE(r.err.find(c.expected), std::string::npos) << c.arguments << "\n" << r.err;
    EXPECT_FALSE(fs::exists(out)) << c.arguments;
    EXPECT_FALSE(fs::exists(dir_ / "t.tpl")) << c.arguments;
  }
}

}  // namespace
