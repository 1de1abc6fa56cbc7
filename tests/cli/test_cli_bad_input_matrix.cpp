// Bad input across the commands, as a table: each case must exit with code 1,
// name the file or option at fault in its message, create nothing, and leave every file
// that was there before (outputs included) byte for byte as it was.
#include <gtest/gtest.h>

#include <cstdint>
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

// A file's text with `from` replaced by `to` (which must be there), written to `to_path`.
void write_edited(const fs::path& from_path, const fs::path& to_path, const std::string& from, const std::string& to) {
  std::string text = slurp(from_path);
  const std::size_t at = text.find(from);
  ASSERT_NE(at, std::string::npos) << from << " not in " << from_path;
  text.replace(at, from.size(), to);
  std::ofstream(to_path, std::ios::binary) << text;
}

// A copy of the BOP scene fixture with one file edited.
void broken_scene(const fs::path& root, const std::string& name, const std::string& file, const std::string& from,
                  const std::string& to) {
  const fs::path scene = root / name / "000001";
  fs::create_directories(scene.parent_path());
  fs::copy(fs::path(FLEXSIGHT_TEST_DATA_DIR) / "bop_tless_like" / "000001", scene, fs::copy_options::recursive);
  write_edited(scene / file, scene / file, from, to);
}

// A copy of the bins with `edit` applied to the second bin.
template <typename Edit>
void broken_bins(const fs::path& root, const std::string& name, Edit edit) {
  fs::copy(root / "bins", root / name, fs::copy_options::recursive);
  edit(root / name / "bin001");
}

class BadInputMatrix : public Cli {
 protected:
  // Inputs that take a command to make, made once: two small bins (synth bin), a
  // template file of one part, and broken copies of them and of the BOP fixture. They
  // live outside the test's folder, which holds the outputs and is compared byte for byte.
  static void SetUpTestSuite() {
    root_ = fresh_temp_dir("BadInputMatrix_data");
    const std::string cad = FLEXSIGHT_TLESS_CAD_DIR;
    fs::create_directories(root_ / "cad1");
    fs::copy(cad + "/obj_02.stl", root_ / "cad1" / "obj_02.stl");
    RunResult r = run_flexsight("pose-templates " + (root_ / "cad1").string() + " -o " + (root_ / "one.tpl").string() +
                                    " --views 1 --points 4 --threads 1",
                                root_);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    r = run_flexsight("synth bin --count 2 --seed 3 --size 64x48 --parts 1..1 --cad " + cad + " -o " +
                          (root_ / "bins").string(),
                      root_);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    {  // a header asking for 3600 in-plane steps (magic 8 bytes, version, views, then the steps)
      fs::copy(root_ / "one.tpl", root_ / "steps3600.tpl");
      std::fstream file(root_ / "steps3600.tpl", std::ios::in | std::ios::out | std::ios::binary);
      file.seekp(16);
      const std::int32_t steps = 3600;
      file.write(reinterpret_cast<const char*>(&steps), sizeof steps);
    }
    const cv::Mat small = flexsight::testing_support::random_rgb8(32, 24, 3);
    broken_bins(root_, "bins_im1_size", [&](const fs::path& bin) { cv::imwrite((bin / "im1.png").string(), small); });
    broken_bins(root_, "bins_passive_size",
                [&](const fs::path& bin) { cv::imwrite((bin / "im0_passive.png").string(), small); });
    broken_bins(root_, "bins_gt_size", [&](const fs::path& bin) {
      flexsight::write_pfm((bin / "disp0GT.pfm").string(), cv::Mat(24, 32, CV_32FC1, cv::Scalar(3)));
    });
    broken_bins(root_, "bins_mask_size", [&](const fs::path& bin) {
      cv::imwrite((bin / "mask0nocc.png").string(), cv::Mat(24, 32, CV_8UC1, cv::Scalar(255)));
    });
    broken_bins(root_, "bins_zero_focal", [&](const fs::path& bin) {
      std::string calib = slurp(bin / "calib.txt");
      calib.replace(calib.find("cam0=[") + 6, calib.find(' ', calib.find("cam0=[")) - calib.find("cam0=[") - 6, "0");
      std::ofstream(bin / "calib.txt") << calib;
    });
    broken_bins(root_, "bins_truncated", [&](const fs::path& bin) {
      const std::string png = slurp(bin / "im1.png");
      std::ofstream(bin / "im1.png", std::ios::binary) << png.substr(0, png.size() / 2);
    });
    broken_bins(root_, "bins_no_calib", [&](const fs::path& bin) { fs::remove(bin / "calib.txt"); });
    // The BOP fixture with one value no camera, pose or box could have.
    const std::string R = "\"cam_R_m2c\": [0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, -1.0], \"cam_t_m2c\": [-7.0";
    broken_scene(root_, "not_a_rotation", "scene_gt.json", R,
                 "\"cam_R_m2c\": [1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0], \"cam_t_m2c\": [-7.0");
    broken_scene(root_, "too_far", "scene_gt.json", "\"cam_t_m2c\": [-7.0, -5.5, 700.0]",
                 "\"cam_t_m2c\": [0.0, 0.0, 1e30]");
    broken_scene(root_, "depth_scale", "scene_camera.json", "\"depth_scale\": 0.1", "\"depth_scale\": 1e308");
    broken_scene(root_, "zero_fx", "scene_camera.json", "[1075.65091572, 0.0, 374.06888344, 0.0, 1073.90347929",
                 "[0.0, 0.0, 374.06888344, 0.0, 0.0");
    broken_scene(root_, "negative_box", "scene_gt_info.json", "\"bbox_visib\": [9, 7, 13, 11]",
                 "\"bbox_visib\": [9, 7, -13, 11]");
    broken_scene(root_, "obj99", "scene_gt.json", "\"obj_id\": 2}", "\"obj_id\": 99}");
    // A box past the second image's edge: found from the image's header before any work,
    // not when that image is loaded (for eval-det with a results file: never).
    broken_scene(root_, "box_past_image", "scene_gt_info.json", "\"bbox_visib\": [20, 10, 7, 5]",
                 "\"bbox_visib\": [20, 10, 7000, 5]");
    // A COCO file whose last image is not the size it says.
    const fs::path coco_copy = root_ / "coco_size";
    fs::copy(fs::path(FLEXSIGHT_TEST_DATA_DIR) / "detect" / "tless_synth_8", coco_copy, fs::copy_options::recursive);
    cv::imwrite((coco_copy / "000000" / "rgb" / "000007.jpg").string(),
                flexsight::testing_support::random_rgb8(320, 300, 5));
    const std::string results = "scene_id,im_id,obj_id,score,R,t,time\n";
    std::ofstream(root_ / "empty.csv");
    std::ofstream(root_ / "header.csv") << results;  // a run that found nothing
    std::ofstream(root_ / "far.csv") << results << "1,0,2,0.75,1 0 0 0 1 0 0 0 1,0 0 1e300,-1\n";
    std::ofstream(root_ / "not_rotation.csv") << results << "1,0,2,0.75,2 0 0 0 1 0 0 0 1,0 0 600,-1\n";
    std::ofstream(root_ / "huge_box.json")
        << R"([{"image_id": 0, "category_id": 14, "bbox": [1, 2, 1e308, 4], "score": 0.5}])";
    std::ofstream(root_ / "negative_box.json")
        << R"([{"image_id": 0, "category_id": 14, "bbox": [1, 2, -3, 4], "score": 0.5}])";
  }
  static void TearDownTestSuite() { fs::remove_all(root_); }

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

  // `also_mention`: a second text the message must hold (the problem beside the file).
  void expect_refused(const std::string& arguments, const std::string& must_mention,
                      const std::string& also_mention = "") {
    SCOPED_TRACE(arguments);
    const auto before = snapshot(dir_);
    const RunResult r = run_flexsight(arguments, dir_);
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_NE(r.err.find("error"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(must_mention), std::string::npos) << "expected '" << must_mention << "' in: " << r.err;
    EXPECT_NE(r.err.find(also_mention), std::string::npos) << "expected '" << also_mention << "' in: " << r.err;
    // Ours is the only complaint: no decoder's own line (libpng's "libpng error: ...").
    EXPECT_EQ(r.err.find("libpng"), std::string::npos) << r.err;
    auto after = snapshot(dir_);
    after.erase("stdout.txt");
    after.erase("stderr.txt");
    auto expected = before;
    expected.erase("stdout.txt");
    expected.erase("stderr.txt");
    EXPECT_EQ(after, expected) << "the run created, changed or removed files";
  }
  static fs::path root_;
};
fs::path BadInputMatrix::root_;

struct Case {
  std::string arguments, must_mention, also_mention;
};

TEST_F(BadInputMatrix, EveryCommandRefusesBadInputAndTouchesNothing) {
  const std::string d = dir_.string() + "/";
  // pick on the fixture's good pair with the junk templates: OPTIONS checked before the
  // output, which exists.
  const auto pick_with = [&](const std::string& options) {
    return "pick " + d + "left.png " + d + "right.png --calib " + d + "calib.txt --templates " + d + "junk.tpl " +
           options + " -o " + d + "existing.json";
  };
  const std::string pair = "stereo " + d + "left.png " + d + "right.png -o " + d + "existing.pfm";
  const std::string cad = FLEXSIGHT_TLESS_CAD_DIR;
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
      {"render " + cad + "/obj_02.stl -o " + d + "existing.png --size 0x10", "--size"},
      {"synth full --count 0 -o " + d + "synth_out", "--count"},
      {"synth full --count 1 --cad " + d + "nowhere -o " + d + "synth_out", d + "nowhere"},
      {"synth bin --count 0 -o " + d + "bins_out", "--count"},
      {"synth bin --count 1 --baseline -1 -o " + d + "bins_out", "--baseline"},
      {"synth bin --count 1 --bin 600x400x100 -o " + d + "bins_out", "--bin"},
      {"synth bin --count 1 --cad " + d + "nowhere -o " + d + "bins_out", d + "nowhere"},
      {"synth bin --count 1 --pile heap -o " + d + "bins_out", "--pile"},
      {"synth bin --count 1 --vary shiny -o " + d + "bins_out", "--vary"},
      {"synth bin --count 1 --noise-level 0..3 -o " + d + "bins_out", "--noise-level"},
      // detection
      {"detect " + d + "nope.png -o " + d + "existing.json", d + "nope.png"},
      {"detect " + d + "left.png --model " + d + "junk.onnx -o " + d + "existing.json", d + "junk.onnx"},
      {"eval-det " + d + "nowhere --results " + d + "existing.json --out " + d + "det_out", d + "nowhere"},
      // --tile: a tile larger than the image (left.png is 64 x 48), auto (needs depth),
      // below the range, or with detections read from a file
      {"detect " + d + "left.png --tile 64 -o " + d + "existing.json", "--tile", d + "left.png (64x48)"},
      {"detect " + d + "left.png --tile auto -o " + d + "existing.json", "--tile", "pick"},
      {"detect " + d + "left.png --tile 12 -o " + d + "existing.json", "--tile"},
      {"eval-det " + std::string(FLEXSIGHT_TEST_DATA_DIR) + "/detect/tless_synth_8 --tile 301 --out " + d + "det_out",
       "--tile", "300x300"},
      {"eval-det " + std::string(FLEXSIGHT_TEST_DATA_DIR) + "/detect/tless_synth_8 --results " + d +
           "existing.json --tile 128 --out " + d + "det_out",
       "--tile", "--results"},
      {"eval-det " + std::string(FLEXSIGHT_TEST_DATA_DIR) + "/detect/tless_synth_8 --results " + d +
           "existing.json --min-visible 0.5 --out " + d + "det_out",
       "--min-visible"},
      {"eval-det " + std::string(FLEXSIGHT_TEST_DATA_DIR) + "/detect/tless_synth_8 --results " + d +
           "existing.json --recall-score 2 --out " + d + "det_out",
       "--recall-score"},
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
      {pick_with("--model " + d + "junk.onnx"), d + "junk.onnx"},
      {"pick " + d + "left.png " + d + "right.png --calib " + d + "calib.txt --templates " + d + "junk.tpl -o " + d +
           "existing.json",
       d + "junk.tpl"},
      {pick_with("--passive-left " + d + "tiny_l.png"), d + "tiny_l.png"},
      {pick_with("--tile 12"), "--tile"},
      {pick_with("--tile 64"), "--tile", d + "left.png (64x48)"},
      {pick_with("--stereo-downscale 0"), "--stereo-downscale"},
      {pick_with("--stereo-plan half"), "--stereo-plan"},
      {pick_with("--refine-boxes sometimes"), "--refine-boxes"},
      {pick_with("--detect-in bins"), "--detect-in"},
      {pick_with("--half-turns maybe"), "--half-turns"},
      {pick_with("--namer " + d + "nope.onnx"), d + "nope.onnx"},
      {pick_with("--namer " + d + "junk.onnx"), d + "junk.onnx"},
      {pick_with("--namer-mix maybe"), "--namer-mix"},
      {pick_with("--retry-below 2"), "--retry-below"},
      {pick_with("--depth-proposals maybe"), "--depth-proposals"},
      {pick_with("--budget-ms -5"), "--budget-ms"},
      {pick_with("--budget-ms soon"), "--budget-ms"},
      {pick_with("--all yes"), "--all", "yes"},
      {pick_with("--all=1"), "--all"},
      {pick_with("--all --budget-ms 500"), "--budget-ms", "--all"},
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
  for (const Case& c : cases) expect_refused(c.arguments, c.must_mention, c.also_mention);
}

// The readers' range checks as the commands meet them, the outputs' folders checked
// before the work, every bin checked before the first, and the bounds of size options.
TEST_F(BadInputMatrix, DataSetsOutputsAndBinsAreCheckedBeforeTheWork) {
  const std::string d = dir_.string() + "/";
  const std::string r = root_.string() + "/";
  const std::string cad = FLEXSIGHT_TLESS_CAD_DIR;
  const std::string mesh = cad + "/obj_02.stl";
  const std::string scene = std::string(FLEXSIGHT_TEST_DATA_DIR) + "/bop_tless_like/000001";
  const std::string coco = std::string(FLEXSIGHT_TEST_DATA_DIR) + "/detect/tless_synth_8";
  const std::string image_pose = "pose " + d + "left.png --depth " + d + "disp.pfm --calib " + d + "calib.txt --boxes " +
                                 d + "existing.json --templates " + r + "one.tpl";
  const std::string pair = "stereo " + d + "left.png " + d + "right.png -o " + d + "existing.pfm";
  const std::string pick = "pick " + d + "left.png " + d + "right.png --calib " + d + "calib.txt --templates " + r +
                           "one.tpl --cad " + r + "cad1";
  const std::string eval_pick = " --templates " + r + "one.tpl --cad " + r + "cad1 --out " + d + "pick_out";
  std::vector<Case> cases = {
      // render --size: bounded like the synth commands', before any allocation
      {"render " + mesh + " -o " + d + "r.png --size 100000x100000", "--size", "16384"},
      {"render " + mesh + " -o " + d + "r.png --size 65536x65536", "--size", "16384"},
      {"render " + mesh + " -o " + d + "r.png --size 46341x46341", "--size", "16384"},
      {"render " + mesh + " -o " + d + "r.png --size 16385x8", "--size", "16384"},
      {"render " + mesh + " -o " + d + "r.png --size 64x48.5", "--size"},
      {"synth full --count 1 --size 16385x100 -o " + d + "synth_out", "--size", "16384"},
      {"synth semi --count 1 --size 100x16385 -o " + d + "synth_out", "--size", "16384"},
      {"synth bin --count 1 --size 16385x16385 -o " + d + "bins_out", "--size", "16384"},
      {"synth bin --count 1 --size 7x48 -o " + d + "bins_out", "--size"},
      // outputs whose folder is missing, or is a file: refused before the work
      {"pose-templates " + r + "cad1 -o " + d + "missing/t.tpl", d + "missing/t.tpl", "folder does not exist"},
      {"pose-templates " + r + "cad1 -o " + d + "existing.png/t.tpl", d + "existing.png/t.tpl", "not a folder"},
      {image_pose + " -o " + d + "missing/p.json", d + "missing/p.json", "folder does not exist"},
      {image_pose + " -o " + d + "p.json --csv " + d + "missing/p.csv", d + "missing/p.csv", "folder does not exist"},
      {image_pose + " -o " + d + "p.json --png " + d + "missing/p.png", d + "missing/p.png", "folder does not exist"},
      {image_pose + " -o " + d + "empty_folder", d + "empty_folder", "it is a folder"},
      {"render " + mesh + " -o " + d + "r.png --depth " + d + "missing/d.pfm", d + "missing/d.pfm"},
      {"render " + mesh + " -o " + d + "r.png --mask " + d + "missing/m.png", d + "missing/m.png"},
      {"render " + mesh + " -o " + d + "existing.png/r.png", d + "existing.png/r.png", "not a folder"},
      {"cloud " + d + "disp.pfm " + d + "left.png --calib " + d + "calib.txt -o " + d + "missing/c.ply",
       d + "missing/c.ply"},
      {"cloud " + d + "disp.pfm " + d + "left.png --calib " + d + "calib.txt --depth " + d + "missing/z.pfm",
       d + "missing/z.pfm"},
      {"cloud " + d + "disp.pfm " + d + "left.png --calib " + d + "calib.txt -o " + d + "empty_folder",
       d + "empty_folder"},
      {pair + " --raw " + d + "missing/raw.pfm", d + "missing/raw.pfm"},
      {pair + " --conf " + d + "missing/conf.pfm", d + "missing/conf.pfm"},
      {pair + " --conf-png " + d + "missing/conf.png", d + "missing/conf.png"},
      {pair + " --calib " + d + "calib.txt --ply " + d + "missing/c.ply", d + "missing/c.ply"},
      {"stereo " + d + "left.png " + d + "right.png -o " + d + "missing/d.pfm", d + "missing/d.pfm"},
      {"detect " + d + "left.png -o " + d + "missing/d.json", d + "missing/d.json"},
      {"detect " + d + "left.png -o " + d + "d.json --png " + d + "missing/d.png", d + "missing/d.png"},
      {pick + " -o " + d + "missing/p.json", d + "missing/p.json"},
      {pick + " --png " + d + "missing/p.png", d + "missing/p.png"},
      {"eval-det " + coco + " --results " + r + "huge_box.json --out " + d + "missing/e", d + "missing/e"},
      {"eval-pose " + scene + " --results " + r + "header.csv --out " + d + "missing/e", d + "missing/e"},
      {"pose " + scene + " --gt-boxes --templates " + r + "one.tpl --out " + d + "missing/e", d + "missing/e"},
      {"eval-pick " + r + "bins --templates " + r + "one.tpl --out " + d + "missing/e", d + "missing/e"},
      {"sensor-plan -o " + d + "missing/plan", d + "missing/plan"},
      {"synth full --count 1 -o " + d + "missing/s", d + "missing/s"},
      {"synth full --count 1 -o " + d + "existing.png/s", d + "existing.png/s"},
      {"synth bin --count 1 -o " + d + "missing/s", d + "missing/s"},
      {"synth patches " + scene + " -o " + d + "missing/s", d + "missing/s"},
      {"synth merge " + d + "nowhere -o " + d + "missing/s", d + "missing/s"},
      // eval-pick: every bin checked (sizes, calibration, truth) before the first is picked
      {"eval-pick " + r + "bins_im1_size" + eval_pick, r + "bins_im1_size/bin001/im1.png", "32x24"},
      {"eval-pick " + r + "bins_passive_size" + eval_pick, r + "bins_passive_size/bin001/im0_passive.png", "32x24"},
      {"eval-pick " + r + "bins_passive_size" + eval_pick + " --pattern-only",
       r + "bins_passive_size/bin001/im0_passive.png", "32x24"},
      {"eval-pick " + r + "bins_gt_size" + eval_pick, r + "bins_gt_size/bin001/disp0GT.pfm", "32x24"},
      {"eval-pick " + r + "bins_mask_size" + eval_pick, r + "bins_mask_size/bin001/mask0nocc.png", "32x24"},
      {"eval-pick " + r + "bins_zero_focal" + eval_pick, r + "bins_zero_focal/bin001/calib.txt", "focal length"},
      {"eval-pick " + r + "bins_truncated" + eval_pick, r + "bins_truncated/bin001/im1.png", "truncated"},
      {"eval-pick " + r + "bins_no_calib" + eval_pick, r + "bins_no_calib/bin001/calib.txt"},
      {"eval-pick " + r + "bins --templates " + r + "steps3600.tpl --cad " + r + "cad1 --out " + d + "pick_out",
       r + "steps3600.tpl", "in_plane_steps"},
      // messages: ours only, naming the file and the problem
      {"detect " + r + "bins_truncated/bin001/im1.png -o " + d + "d.json", r + "bins_truncated/bin001/im1.png",
       "truncated"},
      {"stereo " + d + "left.png " + r + "bins_truncated/bin001/im1.png -o " + d + "existing.pfm",
       r + "bins_truncated/bin001/im1.png", "truncated"},
      {"cloud " + d + "disp.pfm " + r + "bins_truncated/bin001/im1.png --calib " + d + "calib.txt -o " + d + "c.ply",
       r + "bins_truncated/bin001/im1.png", "truncated"},
      {"pick " + r + "bins_truncated/bin001 --templates " + r + "one.tpl", r + "bins_truncated/bin001/im1.png",
       "truncated"},
      {"pick " + r + "bins_zero_focal/bin001 --templates " + r + "one.tpl", r + "bins_zero_focal/bin001/calib.txt",
       "focal length"},
      {"pose-templates " + r + "cad1 -o " + d + "t.tpl --in-plane 361", "--in-plane", "1..360"},
      {"pose-templates " + r + "cad1 -o " + d + "t.tpl --in-plane 3600", "--in-plane", "1..360"},
      {"pose " + d + "left.png --depth " + d + "disp.pfm --calib " + d + "calib.txt --boxes " + d +
           "existing.json --templates " + r + "steps3600.tpl -o " + d + "p.json",
       r + "steps3600.tpl", "in_plane_steps"},
      {"pick " + d + "left.png " + d + "right.png --calib " + d + "calib.txt --templates " + r + "steps3600.tpl",
       r + "steps3600.tpl", "in_plane_steps"},
  };
  // The readers' checks, through every command that reads a BOP scene.
  const std::vector<std::pair<std::string, std::string>> scenes = {
      {"not_a_rotation", "scene_gt.json"}, {"too_far", "scene_gt.json"},          {"depth_scale", "scene_camera.json"},
      {"zero_fx", "scene_camera.json"},    {"negative_box", "scene_gt_info.json"}};
  for (const auto& [name, file] : scenes) {
    const std::string broken = r + name + "/000001";
    cases.push_back({"eval-pose " + broken + " --results " + r + "header.csv --out " + d + "e", broken + "/" + file});
    cases.push_back({"pose " + broken + " --gt-boxes --templates " + r + "one.tpl --out " + d + "e", broken + "/" + file});
    cases.push_back({"eval-det " + broken + " --results " + d + "existing.json --out " + d + "e", broken + "/" + file});
  }
  const std::string past = r + "box_past_image/000001";
  cases.push_back({"pose " + past + " --gt-boxes --templates " + r + "one.tpl --out " + d + "e",
                   past + "/scene_gt_info.json", "reaches beyond the 32x24 image"});
  cases.push_back({"eval-det " + past + " --results " + d + "existing.json --montage 0 --out " + d + "e",
                   past + "/scene_gt_info.json", "reaches beyond the 32x24 image"});
  cases.push_back({"eval-det " + r + "coco_size --results " + d + "existing.json --montage 0 --out " + d + "e",
                   r + "coco_size/000000/rgb/000007.jpg", "is 320x300 but"});
  const std::string obj99 = r + "obj99/000001";
  cases.push_back({"eval-pose " + obj99 + " --results " + r + "header.csv --out " + d + "e", obj99 + "/scene_gt.json",
                   "obj_id 99 has no CAD model"});
  cases.push_back({"pose " + obj99 + " --gt-boxes --templates " + r + "one.tpl --cad " + r + "cad1 --out " + d + "e",
                   obj99 + "/scene_gt.json", "object 99"});
  cases.push_back({"eval-pose " + scene + " --results " + r + "empty.csv --out " + d + "e", r + "empty.csv", "empty"});
  cases.push_back({"eval-pose " + scene + " --results " + r + "far.csv --out " + d + "e", r + "far.csv", "1e+300"});
  cases.push_back({"eval-pose " + scene + " --results " + r + "not_rotation.csv --out " + d + "e",
                   r + "not_rotation.csv", "not a rotation"});
  cases.push_back({"eval-det " + coco + " --results " + r + "huge_box.json --out " + d + "e", r + "huge_box.json",
                   "1e+308"});
  cases.push_back({"eval-det " + coco + " --results " + r + "negative_box.json --out " + d + "e",
                   r + "negative_box.json"});
  ASSERT_GE(cases.size(), 60u);
  for (const Case& c : cases) expect_refused(c.arguments, c.must_mention, c.also_mention);
}

// --parts (known-part mode): an id the detector, the CAD folder or the templates lack, and
// malformed lists, refused naming --parts, the id and what is missing, before any work.
// one.tpl and cad1 hold object 2 alone; the detector knows the 23 parts of the T-LESS CAD.
TEST_F(BadInputMatrix, KnownPartsAreCheckedBeforeTheWork) {
  const std::string d = dir_.string() + "/";
  const std::string r = root_.string() + "/";
  const std::string cad = FLEXSIGHT_TLESS_CAD_DIR;
  const std::string pick = "pick " + d + "left.png " + d + "right.png --calib " + d + "calib.txt --templates " + r +
                           "one.tpl -o " + d + "existing.json --png " + d + "existing.png";
  const std::string eval_pick = "eval-pick " + r + "bins --templates " + r + "one.tpl --out " + d + "pick_out";
  const std::string detect = "detect " + d + "left.png -o " + d + "existing.json";
  const std::string bins = "synth bin --count 1 --size 64x48 -o " + d + "bins_out";
  std::vector<Case> cases = {
      // not a class of the detector
      {detect + " --parts 2,99", "--parts", "object 99 is not a class of the detector"},
      {pick + " --cad " + r + "cad1 --parts 99", "--parts", "object 99 is not a class of the detector"},
      {eval_pick + " --cad " + r + "cad1 --parts 99", "--parts", "object 99 is not a class of the detector"},
      // a class of the detector without a CAD model
      {pick + " --cad " + r + "cad1 --parts 2,4", "--parts", "object 4 has no CAD model in " + r + "cad1"},
      {eval_pick + " --cad " + r + "cad1 --parts 4", "--parts", "object 4 has no CAD model in " + r + "cad1"},
      {bins + " --cad " + r + "cad1 --parts 4", "--parts", "object 4 has no CAD model in " + r + "cad1"},
      // a CAD model without templates
      {pick + " --cad " + cad + " --parts 2,4", "--parts", "object 4 has no templates in " + r + "one.tpl"},
      {eval_pick + " --cad " + cad + " --parts 4", "--parts", "object 4 has no templates in " + r + "one.tpl"},
  };
  // Malformed lists, through every command that takes one.
  const std::vector<std::pair<std::string, std::string>> lists = {
      {"''", "empty list"},        {"2,", "got ''"}, {"2,x", "got 'x'"}, {"2,2", "object 2 is given twice"},
      {"0", "object ids start at 1"}, {"-2", "got '-2'"}};
  for (const auto& [list, problem] : lists) {
    for (const std::string& command : {detect, pick + " --cad " + r + "cad1", eval_pick + " --cad " + r + "cad1", bins}) {
      cases.push_back({command + " --parts " + list, "option --parts", problem});
    }
  }
  for (const Case& c : cases) expect_refused(c.arguments, c.must_mention, c.also_mention);
}

}  // namespace
