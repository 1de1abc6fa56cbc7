// Benchmark folders (host/eval/dataset.h): the scenes found in each layout, on small
// trees the tests write themselves and on the real benchmark copies, from the datasets
// folder of tests/common/real_datasets.h; a missing copy fails those tests.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "host/eval/dataset.h"
#include "host/io/calibration.h"
#include "host/io/input_error.h"
#include "tests/eval/dataset_test_support.h"

namespace flexsight {
namespace {

using namespace dataset_test_support;

void write_v2_scene(const fs::path& folder, const cv::Mat& gt8, const cv::Mat& nonocc) {
  write_png(folder / "imL.png", random_rgb(gt8.cols, gt8.rows, 3));
  write_png(folder / "imR.png", random_rgb(gt8.cols, gt8.rows, 4));
  write_png(folder / "groundtruth.png", gt8);
  write_png(folder / "nonocc.png", nonocc);
}

std::vector<std::string> names_of(const std::vector<Scene>& scenes) {
  std::vector<std::string> names;
  for (const Scene& scene : scenes) names.push_back(scene.name);
  return names;
}

// ---- discovery -------------------------------------------------------------------

void check_real_middeval3(const fs::path& root) {
  const std::vector<Scene> scenes = discover_scenes(root.string());
  const std::vector<std::string> expected = {
      "Adirondack", "ArtL",     "Jadeplant", "Motorcycle", "MotorcycleE",
      "Piano",      "PianoL",   "Pipes",     "Playroom",   "Playtable",
      "PlaytableP", "Recycle",  "Shelves",   "Teddy",      "Vintage"};
  ASSERT_EQ(names_of(scenes), expected);
  for (const Scene& scene : scenes) {
    EXPECT_EQ(scene.layout, DatasetLayout::MiddEval3);
    EXPECT_EQ(scene.ndisp, read_middlebury_calib(scene.calib_path).ndisp) << scene.name;
    EXPECT_FALSE(scene.gt_path.empty()) << scene.name;
    EXPECT_FALSE(scene.nonocc_path.empty()) << scene.name;
  }
  EXPECT_EQ(scenes[0].ndisp, 73);  // Adirondack's calib.txt
  const GroundTruth truth = load_ground_truth(scenes[0]);
  EXPECT_EQ(truth.disparity.size(), cv::Size(718, 496));
  EXPECT_EQ(truth.nonocc.size(), truth.disparity.size());
}

TEST(DiscoverScenes, MiddEval3Tree) {
  TempDir dir;
  const cv::Mat gt = rows_to_mat({{1, 2, 3}, {4, 5, kInf}});
  const cv::Mat mask = rows_to_mask({{255, 128, 255}, {255, 255, 0}});
  write_middeval3_scene(dir / "Beta", gt, mask, 40);
  write_middeval3_scene(dir / "Alpha", gt, mask, 24);
  write_text(dir / "notes" / "README.txt", "not a scene");  // ignored

  const std::vector<Scene> scenes = discover_scenes(dir.path().string());
  ASSERT_EQ(names_of(scenes), (std::vector<std::string>{"Alpha", "Beta"}));
  const Scene& alpha = scenes[0];
  EXPECT_EQ(alpha.layout, DatasetLayout::MiddEval3);
  EXPECT_EQ(alpha.ndisp, 24);
  EXPECT_EQ(scenes[1].ndisp, 40);
  EXPECT_EQ(fs::path(alpha.left_path), dir / "Alpha" / "im0.png");
  EXPECT_EQ(fs::path(alpha.right_path), dir / "Alpha" / "im1.png");
  EXPECT_EQ(fs::path(alpha.gt_path), dir / "Alpha" / "disp0GT.pfm");
  EXPECT_EQ(fs::path(alpha.nonocc_path), dir / "Alpha" / "mask0nocc.png");
  EXPECT_EQ(fs::path(alpha.calib_path), dir / "Alpha" / "calib.txt");
  EXPECT_STREQ(layout_name(alpha.layout), "MiddEval3");

  const GroundTruth truth = load_ground_truth(alpha);
  ASSERT_EQ(truth.disparity.type(), CV_32FC1);
  ASSERT_EQ(truth.disparity.size(), cv::Size(3, 2));
  EXPECT_EQ(truth.disparity.at<float>(1, 1), 5.0f);
  EXPECT_EQ(truth.disparity.at<float>(1, 2), kInf);
  ASSERT_EQ(truth.nonocc.type(), CV_8UC1);
  EXPECT_EQ(truth.nonocc.at<uchar>(0, 1), 128);

  const fs::path real = real_datasets_dir() / "MiddEval3-trainingQ";
  ASSERT_TRUE(real_data_present(real));
  check_real_middeval3(real);
}

TEST(DiscoverScenes, SingleSceneFolder) {
  TempDir dir;
  write_middeval3_scene(dir / "Alpha", rows_to_mat({{1, 2}}), rows_to_mask({{255, 255}}), 16);
  for (const std::string& root : {(dir / "Alpha").string(), (dir / "Alpha").string() + "/"}) {
    const std::vector<Scene> scenes = discover_scenes(root);
    ASSERT_EQ(scenes.size(), 1u) << root;
    EXPECT_EQ(scenes[0].name, "Alpha") << root;
    EXPECT_EQ(scenes[0].ndisp, 16);
  }
  write_v2_scene(dir / "venus", cv::Mat(2, 2, CV_8UC1, cv::Scalar(16)),
                 cv::Mat(2, 2, CV_8UC1, cv::Scalar(255)));
  const std::vector<Scene> v2 = discover_scenes((dir / "venus").string());
  ASSERT_EQ(v2.size(), 1u);
  EXPECT_EQ(v2[0].layout, DatasetLayout::MiddleburyV2);
  EXPECT_EQ(v2[0].ndisp, 32);
}

void check_real_v2(const fs::path& root) {
  const std::vector<Scene> scenes = discover_scenes(root.string());
  ASSERT_EQ(names_of(scenes), (std::vector<std::string>{"cones", "teddy", "tsukuba", "venus"}));
  const int ndisp[] = {64, 64, 16, 32};
  const double scale[] = {4, 4, 16, 8};
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    EXPECT_EQ(scenes[i].ndisp, ndisp[i]) << scenes[i].name;
    EXPECT_EQ(scenes[i].gt_scale, scale[i]) << scenes[i].name;
    const GroundTruth truth = load_ground_truth(scenes[i]);
    EXPECT_EQ(truth.nonocc.size(), truth.disparity.size()) << scenes[i].name;
    double max_disparity = 0;
    cv::minMaxLoc(truth.disparity, nullptr, &max_disparity, nullptr, nullptr,
                  truth.disparity < kInf);
    EXPECT_GT(max_disparity, ndisp[i] / 4) << scenes[i].name;
    EXPECT_LT(max_disparity, ndisp[i]) << scenes[i].name;
  }
  EXPECT_EQ(load_ground_truth(scenes[2]).disparity.size(), cv::Size(384, 288));  // tsukuba
}

TEST(DiscoverScenes, MiddleburyV2Tree) {
  TempDir dir;
  // tsukuba stores disparity * 16: 32 -> 2 px, 0 -> unknown.
  const cv::Mat gt8 = (cv::Mat_<uchar>(2, 3) << 32, 0, 48, 16, 16, 16);
  const cv::Mat nonocc = (cv::Mat_<uchar>(2, 3) << 255, 255, 0, 255, 255, 255);
  write_v2_scene(dir / "tsukuba", gt8, nonocc);
  write_v2_scene(dir / "venus", gt8, nonocc);
  write_v2_scene(dir / "cones", gt8, nonocc);
  write_v2_scene(dir / "mystery", gt8, nonocc);

  const std::vector<Scene> scenes = discover_scenes(dir.path().string());
  ASSERT_EQ(names_of(scenes),
            (std::vector<std::string>{"cones", "mystery", "tsukuba", "venus"}));
  for (const Scene& scene : scenes) EXPECT_EQ(scene.layout, DatasetLayout::MiddleburyV2);
  EXPECT_EQ(scenes[0].gt_scale, 4.0);
  EXPECT_EQ(scenes[0].ndisp, 64);
  EXPECT_EQ(scenes[1].gt_scale, 4.0);  // unknown scene: the common scale
  EXPECT_EQ(scenes[2].gt_scale, 16.0);
  EXPECT_EQ(scenes[2].ndisp, 16);
  EXPECT_EQ(scenes[3].gt_scale, 8.0);
  EXPECT_EQ(scenes[3].ndisp, 32);
  EXPECT_EQ(fs::path(scenes[2].left_path), dir / "tsukuba" / "imL.png");
  EXPECT_EQ(fs::path(scenes[2].right_path), dir / "tsukuba" / "imR.png");
  EXPECT_EQ(fs::path(scenes[2].gt_path), dir / "tsukuba" / "groundtruth.png");
  EXPECT_EQ(fs::path(scenes[2].nonocc_path), dir / "tsukuba" / "nonocc.png");

  const GroundTruth tsukuba = load_ground_truth(scenes[2]);
  EXPECT_EQ(tsukuba.disparity.at<float>(0, 0), 2.0f);
  EXPECT_EQ(tsukuba.disparity.at<float>(0, 1), kInf);
  EXPECT_EQ(tsukuba.disparity.at<float>(0, 2), 3.0f);
  EXPECT_EQ(tsukuba.nonocc.at<uchar>(0, 2), 0);
  EXPECT_EQ(load_ground_truth(scenes[3]).disparity.at<float>(0, 0), 4.0f);  // venus: 32 / 8

  const fs::path real = real_datasets_dir() / "middlebury-v2";
  ASSERT_TRUE(real_data_present(real));
  check_real_v2(real);
}

void check_real_kitti(const fs::path& root) {
  const std::vector<Scene> scenes = discover_scenes(root.string());
  ASSERT_EQ(names_of(scenes), std::vector<std::string>{"000070_10"});
  const Scene& scene = scenes[0];
  EXPECT_EQ(scene.layout, DatasetLayout::Kitti2012);
  EXPECT_EQ(fs::path(scene.left_path).parent_path().filename(), "colored_0");
  EXPECT_EQ(fs::path(scene.calib_path).filename(), "000070.txt");
  EXPECT_EQ(scene.ndisp, 256);
  const GroundTruth truth = load_ground_truth(scene);
  EXPECT_EQ(truth.disparity.size(), cv::Size(1241, 376));
  const int with_gt = cv::countNonZero(truth.disparity < kInf);
  const int nonocc = cv::countNonZero(truth.nonocc == 255);
  EXPECT_GT(nonocc, 0);
  EXPECT_LE(nonocc, with_gt);  // disp_noc is a subset of disp_occ
}

TEST(DiscoverScenes, Kitti2012Tree) {
  TempDir dir;
  const fs::path training = dir / "training";
  for (const char* folder : {"colored_0", "colored_1", "image_0", "image_1"}) {
    write_png(training / folder / "000001_10.png", random_rgb(3, 2, 5));
    write_png(training / folder / "000001_11.png", random_rgb(3, 2, 6));  // no GT frame
  }
  // disparity = value / 256, 0 = none; disp_noc has a subset of disp_occ.
  write_png(training / "disp_occ" / "000001_10.png", rows_to_u16({{256, 512, 0}, {384, 128, 64}}));
  write_png(training / "disp_noc" / "000001_10.png", rows_to_u16({{256, 0, 0}, {384, 128, 0}}));
  write_text(training / "calib" / "000001.txt", "P0: 1 0 0 0 0 1 0 0 0 0 1 0\n");

  const std::vector<Scene> scenes = discover_scenes(dir.path().string());
  ASSERT_EQ(names_of(scenes), std::vector<std::string>{"000001_10"});
  const Scene& scene = scenes[0];
  EXPECT_EQ(scene.layout, DatasetLayout::Kitti2012);
  EXPECT_EQ(fs::path(scene.left_path), training / "colored_0" / "000001_10.png");
  EXPECT_EQ(fs::path(scene.right_path), training / "colored_1" / "000001_10.png");
  EXPECT_EQ(fs::path(scene.gt_path), training / "disp_occ" / "000001_10.png");
  EXPECT_EQ(fs::path(scene.nonocc_path), training / "disp_noc" / "000001_10.png");
  EXPECT_EQ(fs::path(scene.calib_path), training / "calib" / "000001.txt");
  EXPECT_EQ(scene.ndisp, 256);
  // training/ itself is accepted as the root too.
  EXPECT_EQ(names_of(discover_scenes(training.string())), names_of(scenes));

  const GroundTruth truth = load_ground_truth(scene);
  EXPECT_EQ(truth.disparity.at<float>(0, 1), 2.0f);
  EXPECT_EQ(truth.disparity.at<float>(1, 0), 1.5f);
  EXPECT_EQ(truth.disparity.at<float>(0, 2), kInf);
  const cv::Mat expected_nonocc = rows_to_mask({{255, 0, 0}, {255, 255, 0}});
  EXPECT_EQ(cv::countNonZero(truth.nonocc != expected_nonocc), 0);

  // Without colour images the gray ones are used.
  fs::remove_all(training / "colored_0");
  fs::remove_all(training / "colored_1");
  const std::vector<Scene> gray = discover_scenes(dir.path().string());
  ASSERT_EQ(gray.size(), 1u);
  EXPECT_EQ(fs::path(gray[0].left_path), training / "image_0" / "000001_10.png");

  const fs::path real = real_datasets_dir() / "KITTI2012";
  ASSERT_TRUE(real_data_present(real));
  check_real_kitti(real);
}

TEST(DiscoverScenes, Kitti2015Tree) {
  TempDir dir;
  const fs::path training = dir / "training";
  write_png(training / "image_2" / "000000_10.png", random_rgb(3, 2, 7));
  write_png(training / "image_3" / "000000_10.png", random_rgb(3, 2, 8));
  write_png(training / "disp_occ_0" / "000000_10.png", rows_to_u16({{256, 0, 0}, {0, 0, 0}}));
  write_png(training / "disp_noc_0" / "000000_10.png", rows_to_u16({{0, 0, 0}, {0, 0, 0}}));
  const std::vector<Scene> scenes = discover_scenes(dir.path().string());
  ASSERT_EQ(scenes.size(), 1u);
  EXPECT_EQ(scenes[0].layout, DatasetLayout::Kitti2015);
  EXPECT_EQ(fs::path(scenes[0].gt_path), training / "disp_occ_0" / "000000_10.png");
  EXPECT_EQ(fs::path(scenes[0].nonocc_path), training / "disp_noc_0" / "000000_10.png");
  const GroundTruth truth = load_ground_truth(scenes[0]);
  EXPECT_EQ(truth.disparity.at<float>(0, 0), 1.0f);
  EXPECT_EQ(cv::countNonZero(truth.nonocc), 0);
}

TEST(DiscoverScenes, RejectsMissingRootAndUnknownLayout) {
  TempDir dir;
  const std::string missing = (dir / "no_such_folder").string();
  try {
    discover_scenes(missing);
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find(missing), std::string::npos) << error.what();
  }
  EXPECT_THROW(discover_scenes(dir.path().string()), InputError);  // empty folder
  write_text(dir / "something" / "file.txt", "x");
  EXPECT_THROW(discover_scenes(dir.path().string()), InputError);
  write_text(dir / "plain.txt", "x");
  EXPECT_THROW(discover_scenes((dir / "plain.txt").string()), InputError);  // not a folder
}

TEST(LoadGroundTruth, RejectsSceneWithoutGroundTruth) {
  TempDir dir;
  write_middeval3_scene(dir / "Alpha", rows_to_mat({{1, 2}}), rows_to_mask({{255, 255}}), 16);
  fs::remove(dir / "Alpha" / "disp0GT.pfm");
  const std::vector<Scene> scenes = discover_scenes(dir.path().string());
  ASSERT_EQ(scenes.size(), 1u);
  EXPECT_TRUE(scenes[0].gt_path.empty());
  EXPECT_THROW(load_ground_truth(scenes[0]), InputError);
  // A mask of another size than the ground truth is a broken dataset.
  write_pfm_by_hand(dir / "Alpha" / "disp0GT.pfm", rows_to_mat({{1, 2, 3}}));
  EXPECT_THROW(load_ground_truth(discover_scenes(dir.path().string())[0]), InputError);
}

}  // namespace
}  // namespace flexsight
