// Malformed BOP input: each a copy of tests/data/bop_tless_like with one thing wrong,
// and the InputError naming the file and the problem.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "host/dataset/bop_reader.h"
#include "tests/dataset/dataset_test_support.h"

using namespace flexsight;
using namespace flexsight::dataset_test_support;

namespace {

// The fixture copied into the test's scratch folder, with `from` replaced by `to` once in
// the scene's `file`.
class BrokenFixture {
 public:
  BrokenFixture() {
    fs::copy(std::string(FLEXSIGHT_TEST_DATA_DIR) + "/bop_tless_like", dir_ / "split",
             fs::copy_options::recursive);
  }
  std::string scene() const { return dir_ / "split/000001"; }
  std::string split() const { return dir_ / "split"; }
  void replace(const std::string& file, const std::string& from, const std::string& to) {
    const std::string path = scene() + "/" + file;
    std::string text = file_bytes(path);
    const auto at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from << " not in " << path;
    write_file(path, text.replace(at, from.size(), to));
  }

 private:
  ScratchDir dir_;
};

}  // namespace

TEST(BopBadInput, MissingKeyInSceneGtNamesFileImageAndKey) {
  BrokenFixture broken;
  broken.replace("scene_gt.json", ", \"obj_id\": 25", "");
  EXPECT_TRUE(throws_input_error([&] { BopReader reader(broken.split()); }, "000001/scene_gt.json",
                                 "image 0, gt 1: key \"obj_id\" is missing"));
}

TEST(BopBadInput, WrongArrayLengthNamesTheKey) {
  BrokenFixture broken;
  broken.replace("scene_camera.json", "0.0, 0.0, 1.0]", "0.0, 1.0]");
  EXPECT_TRUE(throws_input_error([&] { BopReader reader(broken.split()); },
                                 "000001/scene_camera.json",
                                 "image 0: cam_K: expected 9 numbers, found 8"));
}

TEST(BopBadInput, WrongTypeNamesWhatWasExpected) {
  BrokenFixture broken;
  broken.replace("scene_gt.json", "\"obj_id\": 25", "\"obj_id\": \"25\"");
  EXPECT_TRUE(throws_input_error([&] { BopReader reader(broken.split()); }, "000001/scene_gt.json",
                                 "obj_id: expected an integer"));
}

TEST(BopBadInput, ImageMissingFromSceneGt) {
  BrokenFixture broken;
  broken.replace("scene_gt.json",
                 ",\n  \"1\": [{\"cam_R_m2c\": [0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, -1.0], "
                 "\"cam_t_m2c\": [4.0, -2.5, 650.0], \"obj_id\": 5}]",
                 "");
  EXPECT_TRUE(throws_input_error([&] { BopReader reader(broken.split()); }, "000001/scene_gt.json",
                                 "has no entry for image 1 (scene_camera.json has one)"));
}

TEST(BopBadInput, KeyThatIsNotAnImageId) {
  BrokenFixture broken;
  broken.replace("scene_gt.json", "\"1\": [", "\"one\": [");
  EXPECT_TRUE(throws_input_error([&] { BopReader reader(broken.split()); }, "000001/scene_gt.json",
                                 "key \"one\" is not an image id"));
}

TEST(BopBadInput, GtInfoListingAnotherNumberOfParts) {
  BrokenFixture broken;
  broken.replace("scene_gt_info.json", "\"1\": [{", "\"1\": [{}, {");
  EXPECT_TRUE(throws_input_error([&] { BopReader reader(broken.split()); },
                                 "000001/scene_gt_info.json",
                                 "image 1: lists 2 parts but scene_gt.json lists 1"));
}

TEST(BopBadInput, InvalidJsonGivesTheParserPosition) {
  BrokenFixture broken;
  broken.replace("scene_camera.json", "\"mode\": 0}", "\"mode\": 0");
  EXPECT_TRUE(throws_input_error([&] { BopReader reader(broken.split()); },
                                 "000001/scene_camera.json",
                                 "is not valid JSON (parse error at line"));
}

// Found by tests/fuzz/fuzz_bop_json: nlohmann-json throws out_of_range, not
// parse_error, for a number beyond a double, and it escaped the reader.
TEST(BopBadInput, ANumberBeyondADoubleIsInvalidJson) {
  BrokenFixture broken;
  broken.replace("scene_camera.json", "\"mode\": 0}", "\"mode\": 1e999}");
  EXPECT_TRUE(throws_input_error([&] { BopReader reader(broken.split()); },
                                 "000001/scene_camera.json",
                                 "is not valid JSON (number overflow"));
}

TEST(BopBadInput, DepthScaleIsRequiredBesideDepthImages) {
  BrokenFixture broken;
  broken.replace("scene_camera.json", ", \"depth_scale\": 0.1", "");
  EXPECT_TRUE(throws_input_error([&] { BopReader reader(broken.split()); },
                                 "000001/scene_camera.json",
                                 "image 0: key \"depth_scale\" is missing"));
}

TEST(BopBadInput, MissingRgbAndDepthOfTheWrongSizeAreNamed) {
  BrokenFixture broken;
  fs::remove(broken.scene() + "/rgb/000001.png");
  cv::imwrite(broken.scene() + "/depth/000000.png", cv::Mat(5, 5, CV_16UC1, cv::Scalar(1)));
  const BopReader reader(broken.split());  // images are read by load()
  EXPECT_TRUE(
      throws_input_error([&] { reader.load(1); }, "000001/rgb/000001.png", "does not exist"));
  EXPECT_TRUE(throws_input_error([&] { reader.load(0); }, "000001/depth/000000.png",
                                 "is 5x5 but the rgb image is 32x24"));
}

TEST(BopBadInput, EightBitDepthAndMissingMaskAreNamed) {
  BrokenFixture broken;
  cv::imwrite(broken.scene() + "/depth/000001.png", cv::Mat(24, 32, CV_8UC1, cv::Scalar(1)));
  fs::remove(broken.scene() + "/mask_visib/000000_000001.png");
  const BopReader reader(broken.split());
  EXPECT_TRUE(throws_input_error([&] { reader.load(1); }, "000001/depth/000001.png",
                                 "expected a 16-bit gray depth"));
  EXPECT_TRUE(throws_input_error([&] { reader.load(0); }, "mask_visib/000000_000001.png",
                                 "does not exist"));
}

TEST(BopBadInput, FolderWithoutScenes) {
  ScratchDir dir;
  fs::create_directories(dir / "empty/000001");
  EXPECT_TRUE(throws_input_error([&] { BopReader reader(dir / "empty"); }, "empty",
                                 "neither a BOP scene folder"));
  EXPECT_TRUE(
      throws_input_error([&] { BopReader reader(dir / "missing"); }, "missing", "does not exist"));
}
