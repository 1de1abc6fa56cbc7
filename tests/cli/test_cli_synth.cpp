// Tests of `flexsight synth full` and `synth merge`: a data set made on the command line
// reads back through the project's BOP and COCO readers, is the same bytes whatever the
// thread count, and its shards merged (also through the Slurm / Kubernetes shard
// script) equal the single run.
#include <gtest/gtest.h>

#include "host/dataset/bop_reader.h"
#include "host/dataset/coco_reader.h"
#include "tests/cli/synth_test_support.h"

using namespace flexsight::cli_test_support;

TEST_F(Cli, SynthFullWritesBopCocoAndContactSheet) {
  const fs::path out = dir_ / "data";
  RunResult r = run_flexsight("synth full --count 5" + small_full_options() + " -o " + out.string(),
                              dir_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("5/5 images"), std::string::npos) << r.err;  // the progress line
  const flexsight::BopReader bop(out.string());
  ASSERT_EQ(bop.size(), 5u);
  const flexsight::CocoDataset coco = flexsight::read_coco((out / "coco_instances.json").string());
  ASSERT_EQ(coco.images.size(), 5u);
  size_t visible_parts = 0;
  for (size_t i = 0; i < bop.size(); ++i) {
    const flexsight::AnnotatedImage image = bop.load(i);
    EXPECT_EQ(image.rgb.cols, 96);
    EXPECT_EQ(image.rgb.rows, 72);
    EXPECT_FALSE(image.depth.empty());
    ASSERT_FALSE(image.parts.empty());
    EXPECT_LE(image.parts.size(), 3u);
    for (const flexsight::PartAnnotation& part : image.parts) {
      EXPECT_GE(part.visib_fract, 0.5);
      ASSERT_FALSE(part.mask_visib.empty());
      visible_parts += part.px_count_visib > 0;
    }
  }
  EXPECT_EQ(coco.annotations.size(), visible_parts);
  const cv::Mat sheet = cv::imread((out / "contact_sheet.png").string());
  EXPECT_FALSE(sheet.empty());
  EXPECT_TRUE(no_leftovers(dir_));
}

TEST_F(Cli, SynthFullSameBytesWhateverTheThreadCount) {
  const std::string common = "synth full --count 6" + small_full_options();
  ASSERT_EQ(run_flexsight(common + " --threads 1 -o " + (dir_ / "one").string(), dir_).exit_code, 0);
  ASSERT_EQ(run_flexsight(common + " --threads 2 -o " + (dir_ / "two").string(), dir_).exit_code, 0);
  EXPECT_TRUE(same_folders(dir_ / "one", dir_ / "two"));
}

TEST_F(Cli, SynthShardsMergedEqualTheSingleRun) {
  const std::string common = "synth full --count 7 --rgb png" + small_full_options();
  ASSERT_EQ(run_flexsight(common + " -o " + (dir_ / "single").string(), dir_).exit_code, 0);
  std::string shards;
  for (int i = 0; i < 3; ++i) {
    const std::string shard = (dir_ / ("shard" + std::to_string(i))).string();
    RunResult r = run_flexsight(common + " --shard " + std::to_string(i) + "/3 -o " + shard, dir_);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    shards += " " + shard;
  }
  // A shard left out is refused unless asked for.
  RunResult missing = run_flexsight("synth merge " + (dir_ / "shard0").string() + " " +
                                        (dir_ / "shard2").string() + " -o " + (dir_ / "m").string(),
                                    dir_);
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_NE(missing.err.find("a shard is missing"), std::string::npos) << missing.err;
  EXPECT_FALSE(fs::exists(dir_ / "m"));
  RunResult merged = run_flexsight("synth merge" + shards + " -o " + (dir_ / "merged").string(), dir_);
  ASSERT_EQ(merged.exit_code, 0) << merged.err;
  EXPECT_TRUE(same_folders(dir_ / "single", dir_ / "merged"));
  EXPECT_TRUE(no_leftovers(dir_));
}

// The cluster entry point (scripts/synth/run_shard.sh) as a Slurm array task and as a
// Kubernetes indexed Job pod would run it: the shard index from the scheduler's variable.
TEST_F(Cli, SynthShardScriptUnderSlurmAndKubernetesVariables) {
  const std::string script = std::string(FLEXSIGHT_SOURCE_DIR) + "/scripts/synth/run_shard.sh";
  const std::string common = "FLEXSIGHT=" + std::string(FLEXSIGHT_BINARY) + " COUNT=4 OUT=" +
                             (dir_ / "shards").string() + " SYNTH_ARGS='" + small_full_options() + "' ";
  const std::string log = " > " + (dir_ / "log.txt").string() + " 2>&1";
  ASSERT_EQ(std::system((common + "SLURM_ARRAY_TASK_ID=0 SLURM_ARRAY_TASK_COUNT=2 " + script + log).c_str()), 0)
      << slurp(dir_ / "log.txt");
  ASSERT_EQ(std::system((common + "JOB_COMPLETION_INDEX=1 SHARDS=2 " + script + log).c_str()), 0)
      << slurp(dir_ / "log.txt");
  ASSERT_EQ(run_flexsight("synth full --count 4" + small_full_options() + " -o " +
                              (dir_ / "single").string(), dir_).exit_code, 0);
  RunResult merged = run_flexsight("synth merge " + (dir_ / "shards/shard-00000").string() + " " +
                                       (dir_ / "shards/shard-00001").string() + " -o " +
                                       (dir_ / "merged").string(), dir_);
  ASSERT_EQ(merged.exit_code, 0) << merged.err;
  EXPECT_TRUE(same_folders(dir_ / "single", dir_ / "merged"));
}

TEST_F(Cli, SynthNoMasksNoDepthWriteLess) {
  const fs::path out = dir_ / "lean";
  ASSERT_EQ(run_flexsight("synth full --count 2 --no-masks --no-depth" + small_full_options() +
                              " -o " + out.string(), dir_).exit_code, 0);
  EXPECT_TRUE(fs::exists(out / "000000/rgb"));
  EXPECT_FALSE(fs::exists(out / "000000/depth"));
  EXPECT_FALSE(fs::exists(out / "000000/mask"));
  EXPECT_FALSE(fs::exists(out / "000000/mask_visib"));
  // The COCO file still has the visible masks, as RLE.
  const flexsight::CocoDataset coco = flexsight::read_coco((out / "coco_instances.json").string());
  ASSERT_FALSE(coco.annotations.empty());
}
