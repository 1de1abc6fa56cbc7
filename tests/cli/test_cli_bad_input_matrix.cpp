// Bad input across the commands, as a table: each case must exit with code 1,
// name the file or option at fault in its message, create nothing, and leave every file
// that was there before (outputs included) byte for byte as it was.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "host/io/pfm.h"
#include "tests/cli/cli_test_support.h"
#include "tests/common/test_support.h"

using namespace flexsight::cli_test_support;

namespace {

class BadInputMatrix : public Cli {
 protected:
  void SetUp() override {
    Cli::SetUp();
    auto write = [&](const std::string& name, const std::string& bytes) {
      std::ofstream(dir_ / name, std::ios::binary) << bytes;
    };
    write("calib.txt",
          "cam0=[100 0 30; 0 100 24; 0 0 1]\ncam1=[100 0 34; 0 100 24; 0 0 1]\ndoffs=4\nbaseline=100\n"
          "width=64\nheight=48\nndisp=16\n");
    write("doffs_calib.txt",
          "cam0=[100 0 30; 0 100 24; 0 0 1]\ncam1=[100 0 34; 0 100 24; 0 0 1]\ndoffs=1e300\nbaseline=100\n"
          "width=64\nheight=48\nndisp=16\n");
    write("wide_calib.txt",  // for 640 x 400 images: not a uniform resize of 64 x 48
          "cam0=[100 0 30; 0 100 24; 0 0 1]\ncam1=[100 0 34; 0 100 24; 0 0 1]\ndoffs=4\nbaseline=100\n"
          "width=640\nheight=400\nndisp=16\n");
    write("focal_calib.txt",
          "cam0=[100 0 30; 0 100 24; 0 0 1]\ncam1=[120 0 34; 0 120 24; 0 0 1]\ndoffs=4\nbaseline=100\n"
          "width=64\nheight=48\nndisp=16\n");
    // Outputs that exist already: a failed run must not touch them.
    write("existing.pfm", "the disparity that was here");
    write("existing.ply", "the cloud that was here");
    write("existing.png", "the picture that was here");
    write("existing.json", "the detections that were here");
    write("existing.tpl", "the templates that were here");
    write("junk.onnx", "not a network");
    write("junk.tpl", "not templates");
    write("poses.csv", "scene_id,im_id,obj_id,score,R,t,time\n0,0,1,1,1 0 0 0 1 0 0 0 1,0 0 100\n");
    flexsight::write_pfm((dir_ / "small.pfm").string(), cv::Mat(10, 10, CV_32FC1, cv::Scalar(3)));
    flexsight::write_pfm((dir_ / "disp.pfm").string(), cv::Mat(48, 64, CV_32FC1, cv::Scalar(3)));
    write("trailing.pfm", slurp(dir_ / "disp.pfm") + "xyz");
    write("three_fields.pfm", "Pf\n64 48 7\n-1\n" + std::string(64 * 48 * 4, '\0'));
    cv::imwrite((dir_ / "tiny_l.png").string(), flexsight::testing_support::random_rgb8(8, 8, 1));
    cv::imwrite((dir_ / "tiny_r.png").string(), flexsight::testing_support::random_rgb8(8, 8, 2));
    fs::create_directories(dir_ / "empty_folder");
    // A bin folder without its disparity ground truth.
    fs::create_directories(dir_ / "bins" / "bin000");
    for (const char* name : {"scene_gt.json", "scene_gt_info.json", "scene_camera.json", "im0.png", "im1.png",
                             "calib.txt", "mask0nocc.png", "im0_passive.png", "im1_passive.png"}) {
      write("bins/bin000/" + std::string(name), "{}");
    }
  }

  void expect_refused(const std::string& arguments, const std::string& must_mention) {
    SCOPED_TRACE(arguments);
    const auto before = snapshot(dir_);
    const RunResult r = run_flexsight(arguments, dir_);
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_NE(r.err.find("error"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(must_mention), std::string::npos) << "expected '" << must_mention << "' in: " << r.err;
    auto after = snapshot(dir_);
    after.erase("stdout.txt");
    after.erase("stderr.txt");
    auto expected = before;
    expected.erase("stdout.txt");
    expected.erase("stderr.txt");
    EXPECT_EQ(after, expected) << "the run created, changed or removed files";
  }
};

TEST_F(BadInputMatrix, EveryCommandRefusesBadInputAndTouchesNothing) {
  const std::string d = dir_.string() + "/";
  const std::string pair = "stereo " + d + "left.png " + d + "right.png -o " + d + "existing.pfm";
  const std::string cad = FLEXSIGHT_TLESS_CAD_DIR;
  struct Case {
    std::string arguments, must_mention;
  };
  const std::vector<Case> cases = {
      // stereo
      {"stereo " + d + "left.png " + d + "nope.png -o " + d + "existing.pfm", d + "nope.png"},
      {"stereo " + d + "left.png " + d + "right.png", "-o"},
      {pair + " --ndisp 0", "--ndisp"},
      {pair + " --ndisp 4294967312", "--ndisp"},
      {pair + " --threads 4294967297", "--threads"},
      {pair + " --alpha nan", "--alpha"},
      {pair + " --gamma-distance nan", "--gamma-distance"},
      {pair + " --min-depth nan", "--min-depth"},
      {pair + " --cl-max-memory 12Q", "--cl-max-memory"},
      {pair + " --preset quick", "--preset"},
      {pair + " --ply " + d + "existing.ply", "--calib"},
      {pair + " --calib " + d + "doffs_calib.txt --ply " + d + "existing.ply", d + "doffs_calib.txt"},
      {pair + " --calib " + d + "focal_calib.txt --ply " + d + "existing.ply", d + "focal_calib.txt"},
      {pair + " --ndisp 16 --gt " + d + "small.pfm", d + "small.pfm"},
      {pair + " --ndisp 16 --gt " + d + "three_fields.pfm", d + "three_fields.pfm"},
      {pair + " --ndisp 16 --gt " + d + "trailing.pfm", d + "trailing.pfm"},
      {pair + " --gt-mask " + d + "existing.png", "--gt-mask"},
      {pair + " --png " + d + "no_folder/d.png", d + "no_folder/d.png"},
      {"stereo " + d + "tiny_l.png " + d + "tiny_r.png -o " + d + "existing.pfm --ndisp 2 --method sgbm", "opencv-sgbm"},
      {"stereo " + d + "tiny_l.png " + d + "tiny_r.png -o " + d + "existing.pfm --ndisp 2 --method bm", "opencv-bm"},
      // eval
      {"eval " + d + "nowhere", d + "nowhere"},
      {"eval " + d + "empty_folder --scenes ,", "--scenes"},
      {"eval " + d + "empty_folder --scenes ''", "--scenes"},
      {"eval " + d + "empty_folder --ndisp 5", "--ndisp"},
      {"eval " + d + "empty_folder --repeat 0", "--repeat"},
      // cloud
      {"cloud " + d + "nope.pfm " + d + "left.png --calib " + d + "calib.txt -o " + d + "existing.ply", d + "nope.pfm"},
      {"cloud " + d + "trailing.pfm " + d + "left.png --calib " + d + "calib.txt -o " + d + "existing.ply",
       d + "trailing.pfm"},
      {"cloud " + d + "small.pfm " + d + "left.png --calib " + d + "calib.txt -o " + d + "existing.ply", "the disparity 10x10"},
      {"cloud " + d + "disp.pfm " + d + "left.png --calib " + d + "doffs_calib.txt -o " + d + "existing.ply",
       d + "doffs_calib.txt"},
      // devices
      {"devices --bogus", "--bogus"},
      // render and synth
      {"render " + d + "nope.stl -o " + d + "existing.png", d + "nope.stl"},
      {"render " + cad + "/obj_01.stl -o " + d + "existing.png --size 0x10", "--size"},
      {"synth full --count 0 -o " + d + "synth_out", "--count"},
      {"synth full --count 1 --cad " + d + "nowhere -o " + d + "synth_out", d + "nowhere"},
      {"synth bin --count 0 -o " + d + "bins_out", "--count"},
      {"synth bin --count 1 --baseline -1 -o " + d + "bins_out", "--baseline"},
      {"synth bin --count 1 --bin 600x400x100 -o " + d + "bins_out", "--bin"},
      {"synth bin --count 1 --cad " + d + "nowhere -o " + d + "bins_out", d + "nowhere"},
      // detection
      {"detect " + d + "nope.png -o " + d + "existing.json", d + "nope.png"},
      {"detect " + d + "left.png --model " + d + "junk.onnx -o " + d + "existing.json", d + "junk.onnx"},
      {"eval-det " + d + "nowhere --results " + d + "existing.json --out " + d + "det_out", d + "nowhere"},
      // pose
      {"pose-templates " + d + "nowhere -o " + d + "existing.tpl", d + "nowhere"},
      {"pose " + d + "left.png --depth " + d + "disp.pfm --calib " + d + "calib.txt --boxes " + d +
           "existing.json --templates " + d + "junk.tpl -o " + d + "existing.json",
       d + "junk.tpl"},
      {"eval-pose " + d + "nowhere --results " + d + "poses.csv --out " + d + "pose_out", d + "nowhere"},
      // pick
      {"pick " + d + "left.png " + d + "right.png --calib " + d + "calib.txt -o " + d + "existing.json", "--templates"},
      {"pick " + d + "left.png " + d + "tiny_r.png --calib " + d + "calib.txt --templates " + d + "junk.tpl -o " + d +
           "existing.json",
       d + "tiny_r.png"},
      {"pick " + d + "left.png " + d + "right.png --calib " + d + "wide_calib.txt --templates " + d + "junk.tpl -o " + d +
           "existing.json",
       d + "wide_calib.txt"},
      {"pick " + d + "left.png " + d + "right.png --calib " + d + "doffs_calib.txt --templates " + d + "junk.tpl -o " +
           d + "existing.json",
       d + "doffs_calib.txt"},
      {"pick " + d + "left.png " + d + "right.png --calib " + d + "calib.txt --templates " + d + "junk.tpl --model " +
           d + "junk.onnx -o " + d + "existing.json",
       d + "junk.onnx"},
      {"pick " + d + "left.png " + d + "right.png --calib " + d + "calib.txt --templates " + d + "junk.tpl -o " + d +
           "existing.json",
       d + "junk.tpl"},
      {"pick " + d + "left.png " + d + "right.png --calib " + d + "calib.txt --templates " + d + "junk.tpl --passive-left " +
           d + "tiny_l.png -o " + d + "existing.json",
       d + "tiny_l.png"},
      {"pick " + d + "left.png " + d + "right.png --calib " + d + "calib.txt --templates " + d + "junk.tpl --tile 12 -o " +
           d + "existing.json",
       "--tile"},
      {"pick " + d + "left.png " + d + "right.png --calib " + d + "calib.txt --templates " + d +
           "junk.tpl --stereo-downscale 0 -o " + d + "existing.json",
       "--stereo-downscale"},
      {"pick " + d + "left.png " + d + "right.png --calib " + d + "calib.txt --templates " + d +
           "junk.tpl --half-turns maybe -o " + d + "existing.json",
       "--half-turns"},
      {"pick " + d + "left.png " + d + "right.png --calib " + d + "calib.txt --templates " + d +
           "junk.tpl --retry-below 2 -o " + d + "existing.json",
       "--retry-below"},
      // eval-pick
      {"eval-pick " + d + "empty_folder --out " + d + "pick_out --templates " + d + "junk.tpl", d + "empty_folder"},
      {"eval-pick " + d + "nowhere --out " + d + "pick_out --templates " + d + "junk.tpl", d + "nowhere"},
      {"eval-pick " + d + "bins --templates " + d + "junk.tpl", "--out"},
      {"eval-pick " + d + "bins --out " + d + "pick_out --templates " + d + "junk.tpl", "disp0GT.pfm"},
      {"eval-pick " + d + "bins --out " + d + "pick_out --templates " + d + "junk.tpl --limit 0", "--limit"},
      // sensor planning
      {"sensor-plan --baseline 0 -o " + d + "plan_out", "--baseline"},
      {"sensor-plan --hfov 180 -o " + d + "plan_out", "--hfov"},
      {"sensor-plan --volume 600x400 -o " + d + "plan_out", "--volume"},
      {"sensor-plan -o " + d + "existing.png", d + "existing.png"},
  };
  ASSERT_GE(cases.size(), 30u);
  for (const Case& c : cases) expect_refused(c.arguments, c.must_mention);
}

}  // namespace
