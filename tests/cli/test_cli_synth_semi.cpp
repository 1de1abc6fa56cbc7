// `flexsight synth patches` and `synth semi`: patches cut from a BOP folder (here a
// rendered one, as the demo does for want of real photographs) and pasted on
// backgrounds; the boxes and masks follow the pasted pixels.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "host/dataset/bop_reader.h"
#include "host/dataset/gt_info.h"
#include "tests/cli/synth_test_support.h"

using namespace flexsight::cli_test_support;

TEST_F(Cli, SynthPatchesThenSemi) {
  const fs::path source = dir_ / "source", patches = dir_ / "patches", semi = dir_ / "semi";
  ASSERT_EQ(run_flexsight("synth full --count 6 --min-size 0.4" + small_full_options(1) +
                              " -o " + source.string(), dir_).exit_code, 0);
  RunResult cut = run_flexsight("synth patches " + source.string() + " --min-pixels 50 -o " +
                                    patches.string(), dir_);
  ASSERT_EQ(cut.exit_code, 0) << cut.err;
  int patch_files = 0;
  for (const auto& entry : fs::recursive_directory_iterator(patches)) {
    if (!entry.is_regular_file()) continue;
    ++patch_files;
    const cv::Mat rgba = cv::imread(entry.path().string(), cv::IMREAD_UNCHANGED);
    ASSERT_EQ(rgba.channels(), 4) << entry.path();
    EXPECT_EQ(entry.path().parent_path().filename().string().rfind("obj_", 0), 0u);
  }
  EXPECT_GE(patch_files, 3);

  RunResult r = run_flexsight("synth semi --count 5 --size 96x72 --max-parts 3 --patches " +
                                  patches.string() + " --backgrounds " + FLEXSIGHT_BACKGROUNDS_DIR +
                                  " -o " + semi.string(), dir_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const flexsight::BopReader bop(semi.string());
  ASSERT_EQ(bop.size(), 5u);
  EXPECT_FALSE(fs::exists(semi / "000000/depth"));  // pasted images have no depth
  for (size_t i = 0; i < bop.size(); ++i) {
    const flexsight::AnnotatedImage image = bop.load(i);
    ASSERT_FALSE(image.parts.empty());
    for (const flexsight::PartAnnotation& part : image.parts) {
      EXPECT_GE(part.visib_fract, 0.5);
      // The box is the visible mask's, and the visible mask lies within the full one.
      EXPECT_EQ(flexsight::mask_box(part.mask_visib), part.bbox_visib);
      EXPECT_EQ(cv::countNonZero(part.mask_visib & ~part.mask), 0);
    }
  }
  EXPECT_TRUE(no_leftovers(dir_));
}

TEST_F(Cli, SynthPatchesAndSemiRejectBadInput) {
  const fs::path out = dir_ / "out";
  // A BOP folder without mask_visib cannot give patches.
  const fs::path source = dir_ / "source";
  ASSERT_EQ(run_flexsight("synth full --count 1 --no-masks" + small_full_options() + " -o " +
                              source.string(), dir_).exit_code, 0);
  RunResult r = run_flexsight("synth patches " + source.string() + " -o " + out.string(), dir_);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("mask_visib"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
  // A patch folder with nothing in it, or a patch in a folder without an object id.
  fs::create_directories(dir_ / "no_patches");
  r = run_flexsight("synth semi --count 2 --patches " + (dir_ / "no_patches").string() + " -o " +
                        out.string(), dir_);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("no_patches"), std::string::npos) << r.err;
  fs::create_directories(dir_ / "loose");
  cv::imwrite((dir_ / "loose" / "part.png").string(), cv::Mat(8, 8, CV_8UC4, cv::Scalar::all(255)));
  r = run_flexsight("synth semi --count 2 --patches " + (dir_ / "loose").string() + " -o " +
                        out.string(), dir_);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("part.png"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
  EXPECT_TRUE(no_leftovers(dir_));
}
