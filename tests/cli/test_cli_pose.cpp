// `flexsight pose-templates` and `flexsight pose DATASET --gt-boxes` end to end on a small
// rendered BOP data set of two real T-LESS parts, one part per image, depth with the
// stereo noise model (synth full --depth-noise): the poses, scored by `flexsight
// eval-pose`, are mostly right; and bad input is a clear error, exit code 1, nothing
// written.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "host/dataset/bop_pose_results.h"
#include "host/dataset/bop_reader.h"
#include "host/io/pfm.h"
#include "host/io/input_error.h"
#include "host/pose/template_file.h"
#include "tests/cli/cli_test_support.h"

using namespace flexsight;
using namespace flexsight::cli_test_support;

namespace {

class PoseCli : public ::testing::Test {
 protected:
  // ctest runs each test in its own process, several at once: each process makes its
  // own data folder (the pid in its name), so one never removes another's.
  static void SetUpTestSuite() {
    root_ = fresh_temp_dir("PoseCli_data_" + std::to_string(::getpid()));
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
  for (const char* name : {"poses.csv", "report.md", "report.json", "poses.jpg"}) {
    EXPECT_TRUE(fs::exists(out / name)) << name;
  }
  const auto records = read_bop_pose_results((out / "poses.csv").string());
  EXPECT_EQ(records.size(), 8u);
  const fs::path eval = dir_ / "eval";
  r = run_flexsight("eval-pose " + (root_ / "data").string() + " --results " + (out / "poses.csv").string() +
                        " --cad " + (root_ / "cad").string() + " --out " + eval.string() + " --quiet",
                    dir_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream in(eval / "report.json");
  const auto report = nlohmann::json::parse(in);
  // Measured: ADD(-S) recall 0.5 (4 of 8), VSD AR 0.81: the outlines fit, but obj_21,
  // listed without symmetry, is near-symmetric about its axis and is often posed turned
  // about it (docs/pose.md). Floors that random or unrefined poses fall far below.
  EXPECT_GE(report["add_recall"].get<double>(), 0.25) << report.dump(1);
  EXPECT_GE(report["ar_vsd"].get<double>(), 0.65) << report.dump(1);

  // pose scores what it estimated as eval-pose does, and adds the times.
  std::ifstream own_in(out / "report.json");
  const auto own = nlohmann::json::parse(own_in);
  EXPECT_EQ(own["add_recall"], report["add_recall"]);
  EXPECT_EQ(own["ar"], report["ar"]);
  EXPECT_EQ(own["counts"]["targets"], report["counts"]["targets"]);
  EXPECT_EQ(own["parts_posed"].get<int>(), 8);
  EXPECT_GT(own["wall_ms_per_part"].get<double>(), 0.0);
  for (const char* stage : {"edges", "search", "icp", "score", "total"}) {
    EXPECT_GT(own["median_ms_per_part"][stage].get<double>(), 0.0) << stage;
  }
}

TEST_F(PoseCli, LimitScoresOnlyThePosedImages) {
  const fs::path out = dir_ / "poses";
  const RunResult r = run_flexsight(pose_command("--limit 3 --out " + out.string()), dir_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream in(out / "report.json");
  const auto report = nlohmann::json::parse(in);
  EXPECT_EQ(report["counts"]["images"].get<int>(), 3);
  EXPECT_EQ(report["counts"]["targets"].get<int>(), 3);
  EXPECT_EQ(report["counts"]["estimates"].get<int>(), 3);
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
  // A models_info for other meshes: obj_05's diameter doubled.
  const fs::path other_info = dir_ / "other_models_info.json";
  {
    std::ifstream in(std::string(FLEXSIGHT_SOURCE_DIR) + "/models/tless-cad/models_info.json");
    auto info = nlohmann::json::parse(in);
    info["5"]["diameter"] = 2.0 * info["5"]["diameter"].get<double>();
    std::ofstream(other_info) << info.dump();
  }
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
      {pose_command("--out " + out.string() + " --models-info " + other_info.string()), other_info.string()},
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

// The image form on one image of the data set: its depth as a PFM, a Middlebury calib.txt
// with its camera, its ground-truth box as a COCO detection. Then the bad inputs the
// issue names: depth of another size, a box outside the image, an empty box, an unknown
// object id.
TEST_F(PoseCli, ImageFormPosesTheBoxesOfOneImage) {
  const BopReader reader((root_ / "data").string());
  const AnnotatedImage image = reader.load(0);
  const std::string rgb = (dir_ / "image.png").string();
  cv::Mat bgr;
  cv::cvtColor(image.rgb, bgr, cv::COLOR_RGB2BGR);
  cv::imwrite(rgb, bgr);
  const std::string depth = (dir_ / "depth.pfm").string();
  write_pfm(depth, image.depth);
  const std::string small_depth = (dir_ / "small.pfm").string();
  write_pfm(small_depth, image.depth(cv::Rect(0, 0, 100, 80)).clone());
  const std::string calib = (dir_ / "calib.txt").string();
  {
    const auto& K = image.camera.K;
    std::ofstream out(calib);
    out << "cam0=[" << K(0, 0) << " 0 " << K(0, 2) << "; 0 " << K(1, 1) << " " << K(1, 2) << "; 0 0 1]\n"
        << "cam1=[" << K(0, 0) << " 0 " << K(0, 2) << "; 0 " << K(1, 1) << " " << K(1, 2) << "; 0 0 1]\n"
        << "doffs=0\nbaseline=100\nwidth=" << image.rgb.cols << "\nheight=" << image.rgb.rows << "\nndisp=64\n";
  }
  const BopBox& b = image.parts.at(0).bbox_visib;
  auto boxes = [&](const std::string& name, int obj_id, int x, int y, int w, int h) {
    const std::string path = (dir_ / name).string();
    std::ofstream(path) << "[{\"image_id\": 1, \"category_id\": " << obj_id << ", \"bbox\": [" << x << ", " << y
                        << ", " << w << ", " << h << "], \"score\": 0.9}]";
    return path;
  };
  const std::string good = boxes("boxes.json", image.parts[0].obj_id, b.x, b.y, b.width, b.height);
  const std::string common = " --calib " + calib + " --templates " + (root_ / "parts.tpl").string() + " --cad " +
                             (root_ / "cad").string();
  const fs::path out = dir_ / "poses.json", csv = dir_ / "poses.csv", png = dir_ / "poses.png";
  RunResult r = run_flexsight("pose " + rgb + " --depth " + depth + " --boxes " + good + common + " -o " +
                                  out.string() + " --csv " + csv.string() + " --png " + png.string(),
                              dir_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream in(out);
  const auto poses = nlohmann::json::parse(in);
  ASSERT_EQ(poses.size(), 1u);
  EXPECT_EQ(poses[0]["obj_id"].get<int>(), image.parts[0].obj_id);
  // The translation is the one thing every right or symmetric-twin pose shares.
  const Eigen::Vector3d t(poses[0]["t_mm"][0].get<double>(), poses[0]["t_mm"][1].get<double>(),
                          poses[0]["t_mm"][2].get<double>());
  EXPECT_LT((t - image.parts[0].cam_t_m2c).norm(), 10.0) << t.transpose();
  EXPECT_EQ(read_bop_pose_results(csv.string()).size(), 1u);
  EXPECT_FALSE(cv::imread(png.string()).empty());

  const struct {
    std::string arguments, expected;
  } cases[] = {
      {"pose " + rgb + " --depth " + small_depth + " --boxes " + good + common, "small.pfm"},
      {"pose " + rgb + " --depth " + depth + " --boxes " + boxes("outside.json", image.parts[0].obj_id, 300, 200, 50, 50) + common, "not inside"},
      {"pose " + rgb + " --depth " + depth + " --boxes " + boxes("empty.json", image.parts[0].obj_id, 10, 10, 0, 5) + common, "empty"},
      {"pose " + rgb + " --depth " + depth + " --boxes " + boxes("unknown.json", 7, b.x, b.y, b.width, b.height) + common, "object 7"},
      {"pose " + rgb + " --boxes " + good + common, "--depth"},
  };
  fs::remove(out);
  for (const auto& c : cases) {
    r = run_flexsight(c.arguments + " -o " + out.string(), dir_);
    EXPECT_EQ(r.exit_code, 1) << c.arguments << "\n" << r.err;
    EXPECT_NE(r.err.find(c.expected), std::string::npos) << c.arguments << "\n" << r.err;
    EXPECT_FALSE(fs::exists(out)) << c.arguments;
  }
}

}  // namespace
