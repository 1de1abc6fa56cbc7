// flexsight synth bin from the command line: the files of a bin, the same bytes for the
// same seed whatever the thread count, and bad input refused naming the option, with
// nothing written.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <set>

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
  // --parts without small()'s own --parts 3..3 (a second --parts is an unknown option).
  const std::string unsized = "synth bin --cad " + std::string(FLEXSIGHT_TLESS_CAD_DIR) + " --size 160x120 --count 1";
  expect_rejected(unsized + " --parts 5..2", "--parts: expected MIN..MAX");
  expect_rejected(unsized + " --parts 5..", "--parts: expected a whole number");
  expect_rejected(unsized + " --parts 3", "--parts: object 3 has no CAD model");
  expect_rejected(unsized + " --parts 5,3", "--parts: object 3 has no CAD model");
  expect_rejected(unsized + " --parts 5,5", "--parts: object 5 is given twice");
  expect_rejected(unsized + " --parts 0", "--parts: object ids start at 1");
  expect_rejected(unsized + " --parts -5", "--parts: expected object ids");
  expect_rejected(unsized + " --parts 5,x", "--parts: expected object ids");
  expect_rejected(unsized + " --parts 5,", "--parts: expected object ids");
  expect_rejected(unsized + " --parts ''", "--parts: expected object ids");
  expect_rejected(small() + " --size 0x10", "--size");
  expect_rejected(small("1", "1", (dir_ / "nowhere").string()), "nowhere");
  expect_rejected(small() + " --frobnicate 3", "--frobnicate");
}

// --parts IDS: bins of those parts only, the ids in sim_info.json; without it no
// part_ids key (the default bins' bytes as before).
TEST_F(SynthBin, ChosenPartsMakeBinsOfThosePartsOnly) {
  const std::string base = "synth bin --cad " + std::string(FLEXSIGHT_TLESS_CAD_DIR) +
                           " --size 160x120 --min-parts 6 --max-parts 6 --noise 1 --count 2 --seed 4";
  ASSERT_EQ(run_flexsight(base + " --parts 12,5 -o " + (dir_ / "chosen").string(), dir_).exit_code, 0);
  ASSERT_EQ(run_flexsight(base + " -o " + (dir_ / "all").string(), dir_).exit_code, 0);
  std::set<int> chosen_ids, all_ids;
  for (const char* bin : {"bin000", "bin001"}) {
    for (const auto& [folder, ids] : {std::pair{"chosen", &chosen_ids}, std::pair{"all", &all_ids}}) {
      const auto truth = nlohmann::json::parse(slurp(dir_ / folder / bin / "scene_gt.json"));
      for (const auto& image : truth) {
        for (const auto& part : image) ids->insert(part.at("obj_id").get<int>());
      }
    }
    const auto info = nlohmann::json::parse(slurp(dir_ / "chosen" / bin / "sim_info.json"));
    EXPECT_EQ(info.at("part_ids"), nlohmann::json::array({5, 12}));
    EXPECT_FALSE(nlohmann::json::parse(slurp(dir_ / "all" / bin / "sim_info.json")).contains("part_ids"));
  }
  EXPECT_EQ(chosen_ids, (std::set<int>{5, 12}));  // 12 parts dropped: both drawn
  EXPECT_GT(all_ids.size(), 2u);
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
