// Bad input to `flexsight synth`: every case a clear error naming the file or option,
// exit code 1, and no output folder, no staging folder left behind.
#include <gtest/gtest.h>

#include "tests/cli/synth_test_support.h"

using namespace flexsight::cli_test_support;

namespace {

class SynthErrors : public Cli {
 protected:
  // Runs `arguments` with -o dir/out; it must fail naming `must_mention`.
  void expect_synth_rejected(const std::string& arguments, const std::string& must_mention) {
    const fs::path out = dir_ / "out";
    RunResult r = run_flexsight(arguments + " -o " + out.string(), dir_);
    EXPECT_EQ(r.exit_code, 1) << arguments << "\n" << r.err;
    EXPECT_NE(r.err.find("error"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(must_mention), std::string::npos) << arguments << "\n" << r.err;
    EXPECT_FALSE(fs::exists(out)) << arguments;
    EXPECT_TRUE(no_leftovers(dir_));
  }
  // A CAD folder holding one good model and `bad` (a file of tests/data/render).
  std::string cad_with(const std::string& bad) {
    const fs::path cad = dir_ / ("cad_" + bad);
    fs::create_directories(cad);
    fs::copy_file(std::string(FLEXSIGHT_TLESS_CAD_DIR) + "/obj_05.stl", cad / "obj_05.stl");
    fs::copy_file(std::string(FLEXSIGHT_TEST_DATA_DIR) + "/render/" + bad,
                  cad / ("obj_09" + fs::path(bad).extension().string()));
    return cad.string();
  }
  std::string backgrounds() const { return std::string(" --backgrounds ") + FLEXSIGHT_BACKGROUNDS_DIR; }
  std::string cad() const { return std::string(" --cad ") + FLEXSIGHT_TLESS_CAD_DIR; }
};

}  // namespace

TEST_F(SynthErrors, UnreadableOrEmptyMeshes) {
  expect_synth_rejected("synth full --count 2 --cad " + cad_with("not_a_mesh.ply") + backgrounds(),
                        "obj_09.ply");
  expect_synth_rejected("synth full --count 2 --cad " + cad_with("empty.stl") + backgrounds(),
                        "obj_09.stl");
  expect_synth_rejected("synth full --count 2 --cad " + cad_with("points_only.ply") + backgrounds(),
                        "obj_09.ply");
  fs::create_directories(dir_ / "no_meshes");
  expect_synth_rejected("synth full --count 2 --cad " + (dir_ / "no_meshes").string() + backgrounds(),
                        "no_meshes");
  expect_synth_rejected("synth full --count 2 --cad " + (dir_ / "nowhere").string() + backgrounds(),
                        "nowhere");
}

TEST_F(SynthErrors, MissingEmptyOrBrokenBackgrounds) {
  expect_synth_rejected("synth full --count 2" + cad() + " --backgrounds " +
                            (dir_ / "nowhere").string(), "nowhere");
  fs::create_directories(dir_ / "empty_backgrounds");
  expect_synth_rejected("synth full --count 2" + cad() + " --backgrounds " +
                            (dir_ / "empty_backgrounds").string(), "empty_backgrounds");
  fs::create_directories(dir_ / "broken");
  std::ofstream(dir_ / "broken" / "photo.jpg") << "not a jpeg";
  expect_synth_rejected("synth full --count 2" + cad() + " --backgrounds " +
                            (dir_ / "broken").string(), "photo.jpg");
}

TEST_F(SynthErrors, ImpossibleCountsSizesAndPartNumbers) {
  const std::string data = cad() + backgrounds();
  expect_synth_rejected("synth full --count 0" + data, "--count");
  expect_synth_rejected("synth full --count 4x" + data, "--count");
  expect_synth_rejected("synth full" + data, "--count");
  expect_synth_rejected("synth full --count 3 --shard 3/3" + data, "--shard");
  expect_synth_rejected("synth full --count 3 --shard 0/0" + data, "--shard");
  expect_synth_rejected("synth full --count 3 --shard 0/4" + data, "--shard");
  expect_synth_rejected("synth full --count 3 --shard 1" + data, "--shard");
  expect_synth_rejected("synth full --count 3 --size 0x300" + data, "--size");
  expect_synth_rejected("synth full --count 3 --size 300" + data, "--size");
  expect_synth_rejected("synth full --count 3 --min-parts 0" + data, "--min-parts");
  expect_synth_rejected("synth full --count 3 --min-parts 4 --max-parts 2" + data, "--min-parts");
  expect_synth_rejected("synth full --count 3 --max-parts 2.5" + data, "--max-parts");
  expect_synth_rejected("synth full --count 3 --min-size 0" + data, "--min-size");
  expect_synth_rejected("synth full --count 3 --min-visible nan" + data, "--min-visible");
  expect_synth_rejected("synth full --count 3 --rgb tiff" + data, "--rgb");
  expect_synth_rejected("synth full --count 3 --no-such-option 1" + data, "--no-such-option");
}

TEST_F(SynthErrors, NonEmptyOutputIsKeptUnlessOverwrite) {
  const fs::path out = dir_ / "out";
  fs::create_directories(out);
  std::ofstream(out / "precious.txt") << "keep me";
  const std::string command = "synth full --count 2" + small_full_options() + " -o " + out.string();
  RunResult refused = run_flexsight(command, dir_);
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_NE(refused.err.find("--overwrite"), std::string::npos) << refused.err;
  EXPECT_EQ(slurp(out / "precious.txt"), "keep me");
  RunResult replaced = run_flexsight(command + " --overwrite", dir_);
  ASSERT_EQ(replaced.exit_code, 0) << replaced.err;
  EXPECT_FALSE(fs::exists(out / "precious.txt"));
  EXPECT_TRUE(fs::exists(out / "dataset_info.json"));
}

TEST_F(SynthErrors, MergeRefusesUnfinishedOrMismatchedShards) {
  const std::string base = "synth full --count 4" + small_full_options();
  ASSERT_EQ(run_flexsight(base + " --shard 0/2 -o " + (dir_ / "a").string(), dir_).exit_code, 0);
  ASSERT_EQ(run_flexsight(base + " --seed 8 --shard 1/2 -o " + (dir_ / "b").string(), dir_).exit_code, 0);
  expect_synth_rejected("synth merge " + (dir_ / "a").string() + " " + (dir_ / "b").string(),
                        "dataset_info.json");
  expect_synth_rejected("synth merge " + (dir_ / "a").string() + " " + (dir_ / "a").string(), "");
  fs::create_directories(dir_ / "unfinished");
  expect_synth_rejected("synth merge " + (dir_ / "a").string() + " " + (dir_ / "unfinished").string(),
                        "unfinished");
}
