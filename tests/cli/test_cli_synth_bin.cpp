// flexsight synth bin from the command line: the files of a bin, the same bytes for the
// same seed whatever the thread count, and bad input refused naming the option, with
// nothing written.
#include <gtest/gtest.h>

#include "host/eval/dataset.h"
#include "tests/cli/synth_test_support.h"

using namespace flexsight::cli_test_support;

namespace {

class SynthBin : public Cli {
 protected:
  // One small bin (--count 1 unless `count` says otherwise).
  std::string small(const std::string& seed = "1", const std::string& count = "1",
                    const std::string& cad = FLEXSIGHT_TLESS_CAD_DIR) const {
    return "synth bin --cad " + cad + " --size 160x120 --parts 3..3 --noise 1 --count " + count +
           " --seed " + seed;
  }
  void expect_rejected(const std::string& arguments, const std::string& must_mention) {
    const fs::path out = dir_ / "bins";
    RunResult r = run_flexsight(arguments + " -o " + out.string(), dir_);
    EXPECT_EQ(r.exit_code, 1) << arguments << "\n" << r.err;
    EXPECT_NE(r.err.find(must_mention), std::string::npos) << arguments << "\n" << r.err;
    EXPECT_FALSE(fs::exists(out)) << arguments;
    EXPECT_TRUE(no_leftovers(dir_));
  }
};

}  // namespace

TEST_F(SynthBin, WritesAMiddEval3AndBopScenePerBin) {
  RunResult r = run_flexsight(small("1", "2") + " -o " + (dir_ / "bins").string(), dir_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* bin : {"bin000", "bin001"}) {
    for (const char* file : {"calib.txt", "im0.png", "im1.png", "im0_passive.png", "im1_passive.png",
                             "disp0GT.pfm", "disp1GT.pfm", "mask0nocc.png", "scene_camera.json",
                             "scene_gt.json", "scene_gt_info.json", "sim_info.json"}) {
      EXPECT_TRUE(fs::is_regular_file(dir_ / "bins" / bin / file)) << bin << "/" << file;
    }
    EXPECT_TRUE(fs::is_directory(dir_ / "bins" / bin / "mask_visib"));
  }
  // flexsight eval finds them as MiddEval3 scenes with ground truth.
  const auto scenes = flexsight::discover_scenes((dir_ / "bins").string());
  ASSERT_EQ(scenes.size(), 2u);
  EXPECT_FALSE(scenes[0].gt_path.empty());
  EXPECT_FALSE(scenes[0].nonocc_path.empty());
  EXPECT_GT(scenes[0].ndisp, 0);
}

TEST_F(SynthBin, SameSeedSameBytesAnyThreadCount) {
  ASSERT_EQ(run_flexsight(small("5") + " --threads 1 -o " + (dir_ / "a").string(), dir_).exit_code, 0);
  ASSERT_EQ(run_flexsight(small("5") + " --threads 3 -o " + (dir_ / "b").string(), dir_).exit_code, 0);
  ASSERT_EQ(run_flexsight(small("6") + " --threads 1 -o " + (dir_ / "c").string(), dir_).exit_code, 0);
  EXPECT_TRUE(same_folders(dir_ / "a", dir_ / "b"));
  EXPECT_FALSE(same_folders(dir_ / "a", dir_ / "c"));
}

TEST_F(SynthBin, BadInputNamesTheOptionAndWritesNothing) {
  expect_rejected(small("1", "0"), "--count");
  expect_rejected(small() + " --baseline 0", "--baseline");
  expect_rejected(small() + " --baseline -500", "--baseline");
  expect_rejected(small() + " --baseline nan", "baseline");
  expect_rejected(small() + " --bin 700x340x120", "--bin");
  expect_rejected(small() + " --bin 500x340", "--bin");
  expect_rejected(small() + " --volume 600x400x3000", "--distance");
  expect_rejected(small() + " --focal 5000", "--focal");
  expect_rejected(small() + " --projector-fov 180", "--projector-fov");
  expect_rejected(small() + " --dots 0", "--dots");
  expect_rejected(small() + " --parts 5..2", "--parts");
  expect_rejected(small() + " --parts 5", "--parts");
  expect_rejected(small() + " --size 0x10", "--size");
  expect_rejected(small("1", "1", (dir_ / "nowhere").string()), "nowhere");
  expect_rejected(small() + " --frobnicate 3", "--frobnicate");
}

TEST_F(SynthBin, ExistingBinsAreKeptWithoutOverwrite) {
  const fs::path out = dir_ / "bins";
  ASSERT_EQ(run_flexsight(small() + " -o " + out.string(), dir_).exit_code, 0);
  const auto before = folder_bytes(out);
  RunResult r = run_flexsight(small("9") + " -o " + out.string(), dir_);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("--overwrite"), std::string::npos) << r.err;
  EXPECT_EQ(folder_bytes(out), before);
  ASSERT_EQ(run_flexsight(small("9") + " --overwrite -o " + out.string(), dir_).exit_code, 0);
  EXPECT_NE(folder_bytes(out), before);
}

TEST_F(SynthBin, PileAndVaryOptionsOutOfRangeNameTheOptionAndWriteNothing) {
  expect_rejected(small() + " --pile heap", "--pile");
  expect_rejected(small() + " --pile", "--pile");
  expect_rejected(small() + " --vary shiny", "--vary");
  expect_rejected(small() + " --vary material,,lights", "--vary");
  expect_rejected(small() + " --vary material,", "--vary");
  expect_rejected(small() + " --noise-level 0.5..0.2", "--noise-level");
  expect_rejected(small() + " --noise-level 0..2", "--noise-level");
  expect_rejected(small() + " --noise-level loud", "--noise-level");
}

TEST_F(SynthBin, VariedBinsRecordTheirDrawsAndRepeatByteForByte) {
  const std::string varied = small("4") + " --vary all";
  ASSERT_EQ(run_flexsight(varied + " --threads 1 -o " + (dir_ / "a").string(), dir_).exit_code, 0);
  ASSERT_EQ(run_flexsight(varied + " --threads 3 -o " + (dir_ / "b").string(), dir_).exit_code, 0);
  ASSERT_EQ(run_flexsight(small("4") + " -o " + (dir_ / "c").string(), dir_).exit_code, 0);
  EXPECT_TRUE(same_folders(dir_ / "a", dir_ / "b"));
  EXPECT_FALSE(same_folders(dir_ / "a", dir_ / "c"));
  const std::string info = slurp(dir_ / "a" / "bin000" / "sim_info.json");
  for (const char* key : {"\"variation\"", "\"metal_share\"", "\"lamps\"", "\"dot_blur_degrees\"", "\"gain\"",
                          "\"vignetting\"", "\"noise_level\""}) {
    EXPECT_NE(info.find(key), std::string::npos) << key;
  }
  EXPECT_EQ(slurp(dir_ / "c" / "bin000" / "sim_info.json").find("variation"), std::string::npos);
}
