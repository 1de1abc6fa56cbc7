// The flexsight binary end to end, render command: a picture, depth and mask that agree
// with the scene, the same bytes run after run, and bad meshes or options refused.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "host/io/pfm.h"
#include "tests/cli/cli_test_support.h"
#include "tests/common/test_support.h"

using namespace flexsight::cli_test_support;

// flexsight render: the fixture cube at 200 mm in front of its floor. The picture, the
// depth and the mask agree with the scene: the cube in the middle, nearer than its
// centre by at most half its diagonal, the floor at 200 mm + 1.1 x the cube's diagonal / 2.
TEST_F(Cli, RenderWritesPictureDepthAndMask) {
  const std::string cube = std::string(FLEXSIGHT_TEST_DATA_DIR) + "/render/cube.obj";
  const std::string picture = (dir_ / "cube.png").string();
  const std::string depth = (dir_ / "cube_depth.pfm").string();
  const std::string mask = (dir_ / "cube_mask.png").string();
  RunResult r = run_flexsight("render " + cube + " -o " + picture + " --depth " + depth +
                                  " --mask " + mask + " --size 81x61 --focal 100 --distance 200" +
                                  " --light-radius 10 --shadow-samples 2 --threads 2",
                              dir_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const cv::Mat rgb = cv::imread(picture, cv::IMREAD_UNCHANGED);
  ASSERT_EQ(rgb.type(), CV_8UC3);
  EXPECT_EQ(rgb.size(), cv::Size(81, 61));
  const cv::Mat z = flexsight::read_pfm(depth);
  const cv::Mat ids = cv::imread(mask, cv::IMREAD_UNCHANGED);
  ASSERT_EQ(ids.type(), CV_8UC1);
  ASSERT_EQ(z.size(), ids.size());
  EXPECT_EQ(ids.at<std::uint8_t>(30, 40), 1);
  EXPECT_EQ(ids.at<std::uint8_t>(0, 0), 0);
  const float half_diagonal = 10.0f * std::sqrt(3.0f);
  int cube_pixels = 0;
  for (int y = 0; y < z.rows; ++y) {
    for (int x = 0; x < z.cols; ++x) {
      const float d = z.at<float>(y, x);
      if (ids.at<std::uint8_t>(y, x) == 1) {
        ++cube_pixels;
        EXPECT_GE(d, 200.0f - half_diagonal - 1e-3f);
        EXPECT_LE(d, 200.0f + half_diagonal);
      } else {
        EXPECT_NEAR(d, 200.0f + 1.1f * half_diagonal, 1e-3f);
      }
    }
  }
  // The cube spans about 20 to 35 mm across at 200 mm: 10 to 17 pixels at focal 100.
  EXPECT_GT(cube_pixels, 100);
  EXPECT_LT(cube_pixels, 17 * 17);
  // The same command again gives the same bytes.
  const std::string again = (dir_ / "again.png").string();
  ASSERT_EQ(run_flexsight("render " + cube + " -o " + again +
                              " --size 81x61 --focal 100 --distance 200 --light-radius 10" +
                              " --shadow-samples 2 --threads 1",
                          dir_)
                .exit_code,
            0);
  EXPECT_TRUE(flexsight::testing_support::same_bytes(rgb, cv::imread(again, cv::IMREAD_UNCHANGED)));
}

TEST_F(Cli, RenderRejectsBadMeshesAndOptionsWithoutWriting) {
  const std::string cube = std::string(FLEXSIGHT_TEST_DATA_DIR) + "/render/cube.obj";
  const std::string empty = std::string(FLEXSIGHT_TEST_DATA_DIR) + "/render/empty.stl";
  const std::string missing = (dir_ / "missing.stl").string();
  const std::string picture = (dir_ / "picture.png").string();
  const std::pair<std::string, std::string> cases[] = {
      {"render " + missing + " -o " + picture, missing},
      {"render " + empty + " -o " + picture, empty + ": is empty"},
      {"render " + cube + " " + missing + " -o " + picture, missing},
      {"render " + cube + " -o " + picture + " --size 0x10", "option --size"},
      {"render " + cube + " -o " + picture + " --rotation 1,2", "option --rotation"},
      {"render " + cube + " -o " + picture + " --light-radius -1", "option --light-radius"},
      {"render " + cube + " -o " + picture + " --focal -5", "camera"},
      {"render " + cube + " -o " + picture + " --frobnicate 1", "--frobnicate"},
      {"render " + cube, "option -o"},
      {"render " + cube + " -o " + (dir_ / "no_folder" / "p.png").string(), "folder does not exist"},
  };
  for (const auto& [arguments, mention] : cases) {
    RunResult r = run_flexsight(arguments, dir_);
    EXPECT_EQ(r.exit_code, 1) << arguments << ": " << r.err;
    EXPECT_NE(r.err.find("error"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(mention), std::string::npos) << arguments << ": " << r.err;
    EXPECT_FALSE(fs::exists(picture)) << arguments;
  }
}
