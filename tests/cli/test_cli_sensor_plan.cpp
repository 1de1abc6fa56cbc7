// flexsight sensor-plan end to end: the paper's camera by default, the files of -o, and
// bad input (exit 1, the option named, nothing written).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "tests/cli/cli_test_support.h"

using namespace flexsight::cli_test_support;

namespace {

class SensorPlanCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fresh_temp_dir(::testing::UnitTest::GetInstance()->current_test_info()->name());
    out_ = dir_ / "plan";
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir_);
  }
  // Only the run's captured output may be left in the test folder.
  void expect_nothing_written() {
    for (const auto& entry : fs::directory_iterator(dir_)) {
      const std::string name = entry.path().filename().string();
      EXPECT_TRUE(name == "stdout.txt" || name == "stderr.txt") << "left behind: " << name;
    }
  }
  void expect_rejected(const std::string& options, const std::string& must_mention) {
    RunResult r = run_flexsight("sensor-plan " + options + " -o " + out_.string(), dir_);
    EXPECT_EQ(r.exit_code, 1) << options << "\n" << r.err;
    EXPECT_NE(r.err.find("error"), std::string::npos) << options << "\n" << r.err;
    EXPECT_NE(r.err.find(must_mention), std::string::npos) << options << "\n" << r.err;
    EXPECT_TRUE(r.out.empty()) << options << "\n" << r.out;
    expect_nothing_written();
  }
  fs::path dir_, out_;
};

TEST_F(SensorPlanCli, DefaultsAreThePaperCameraAndWriteTheFourFiles) {
  RunResult r = run_flexsight("sensor-plan -o " + out_.string(), dir_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("Coverage"), std::string::npos);
  EXPECT_NE(r.out.find("7000.0 px"), std::string::npos) << r.out;
  for (const char* name : {"report.md", "report.json", "top.png", "side.png"}) {
    EXPECT_TRUE(fs::is_regular_file(out_ / name)) << name;
  }
  EXPECT_EQ(std::distance(fs::directory_iterator(out_), fs::directory_iterator()), 4);
  for (const char* name : {"top.png", "side.png"}) {
    const cv::Mat picture = cv::imread((out_ / name).string());
    EXPECT_GT(picture.cols, 500) << name;
    EXPECT_GT(picture.rows, 500) << name;
  }
  const auto json = nlohmann::json::parse(slurp(out_ / "report.json"));
  for (const char* key : {"inputs", "camera", "coverage", "depth_resolution", "disparity", "target_dz"}) {
    EXPECT_TRUE(json.contains(key)) << key;
  }
  EXPECT_DOUBLE_EQ(json["inputs"]["baseline_mm"].get<double>(), 500.0);
  EXPECT_NEAR(json["camera"]["focal_px"].get<double>(), 7000.0, 1e-6);
  EXPECT_DOUBLE_EQ(json["coverage"]["all_percent"].get<double>(), 100.0);
  EXPECT_EQ(json["coverage"]["faces"].size(), 6u);
  EXPECT_EQ(json["coverage"]["corners"].size(), 8u);
  EXPECT_TRUE(json["coverage"]["unseen_box_mm"].is_null());
  EXPECT_NEAR(json["depth_resolution"]["dz_far_mm"].get<double>(), 1450.0 * 1450.0 / 16.0 / 3.5e6, 1e-9);
  EXPECT_NEAR(json["disparity"]["max_px"].get<double>(), 0.0, 1e-9);
  EXPECT_NEAR(json["disparity"]["min_px"].get<double>(), 3.5e6 / 1450.0 - 3.5e6 / 1050.0, 1e-9);
  EXPECT_EQ(json["disparity"]["ndisp"].get<int>(), 921);
  EXPECT_NEAR(json["target_dz"]["subpixel_px_at_focal"].get<double>(), 0.4994, 1e-4);
  EXPECT_NE(slurp(out_ / "report.md").find("| volume | 100.0 %"), std::string::npos);
}

TEST_F(SensorPlanCli, HelpListsTheOptions) {
  RunResult r = run_flexsight("sensor-plan --help", dir_);
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("usage: flexsight sensor-plan"), std::string::npos) << r.out;
  for (const char* option : {"--baseline", "--distance", "--focal", "--hfov", "--size", "--pixel-um", "--doffs",
                             "--projector-fov", "--projector-offset", "--volume", "--subpixel", "--grid"}) {
    EXPECT_NE(r.out.find(option), std::string::npos) << option;
  }
  expect_nothing_written();
}

TEST_F(SensorPlanCli, WithoutOutputFolderOnlyPrints) {
  RunResult r = run_flexsight("sensor-plan --hfov 40 --subpixel 1/4", dir_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("0.25 px"), std::string::npos) << r.out;
  expect_nothing_written();
}

TEST_F(SensorPlanCli, VolumePartlyOutsideTheViewsIsReportedNotRejected) {
  RunResult r = run_flexsight("sensor-plan --focal 9000 --doffs 3000 -o " + out_.string(), dir_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto json = nlohmann::json::parse(slurp(out_ / "report.json"));
  const double all = json["coverage"]["all_percent"].get<double>();
  EXPECT_GT(all, 50.0);
  EXPECT_LT(all, 100.0);
  EXPECT_FALSE(json["coverage"]["unseen_box_mm"].is_null());
  EXPECT_NE(r.out.find("unseen region"), std::string::npos);
}

TEST_F(SensorPlanCli, BadInputNamesTheOptionAndWritesNothing) {
  const std::pair<const char*, const char*> cases[] = {
      {"--baseline 0", "--baseline"},
      {"--baseline -500", "--baseline"},
      {"--baseline abc", "baseline"},
      {"--distance 0", "--distance"},
      {"--distance 150", "--distance"},  // the 400 mm deep volume would reach behind the rig
      {"--hfov 0", "--hfov"},
      {"--hfov 180", "--hfov"},
      {"--hfov -10", "--hfov"},
      {"--focal 7000 --hfov 30", "--focal"},
      {"--focal 0", "--focal"},
      {"--focal nan", "focal"},
      {"--size 4000", "--size"},
      {"--size 0x3000", "--size"},
      {"--size 4000x3000x3", "--size"},
      {"--size 4000x-3000", "--size"},
      {"--pixel-um 0", "--pixel-um"},
      {"--projector-fov 35", "--projector-fov"},
      {"--projector-fov 0x35", "--projector-fov"},
      {"--projector-fov 35x180", "--projector-fov"},
      {"--projector-offset 300", "--projector-offset"},
      {"--volume 600x400", "--volume"},
      {"--volume 600x0x400", "--volume"},
      {"--volume 600x400x-1", "--volume"},
      {"--subpixel 0", "--subpixel"},
      {"--subpixel 1/0", "--subpixel"},
      {"--subpixel x", "subpixel"},
      {"--target-dz -1", "--target-dz"},
      {"--grid 0", "--grid"},
      {"--grid 0.01", "--grid"},
      {"--doffs many", "doffs"},
      {"--doffs 100000", "working volume"},  // nothing seen by both cameras
      {"--frobnicate 3", "--frobnicate"},
      {"stray", "stray"},
  };
  for (const auto& [options, mention] : cases) expect_rejected(options, mention);
}

TEST_F(SensorPlanCli, ExistingOutputFolderIsKeptWithoutOverwrite) {
  fs::create_directories(out_);
  std::ofstream(out_ / "keep.txt") << "mine";
  RunResult r = run_flexsight("sensor-plan -o " + out_.string(), dir_);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("-o"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(out_ / "keep.txt"), "mine");
  EXPECT_FALSE(fs::exists(out_ / "report.json"));
  r = run_flexsight("sensor-plan --overwrite -o " + out_.string(), dir_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(fs::exists(out_ / "keep.txt"));
  EXPECT_TRUE(fs::exists(out_ / "report.json"));
}

}  // namespace
