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

// Values that parse but describe no camera or pose: refused where they are read, with the
// file and entry named, before a renderer or a search meets them.
TEST(BopBadInput, GroundTruthRotationThatIsNotARotation) {
  const std::string good = "\"cam_R_m2c\": [0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, -1.0], "
                           "\"cam_t_m2c\": [-7.0";
  for (const char* R : {"1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0",
                        "0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0",
                        "0.0, 2.0, 0.0, 2.0, 0.0, 0.0, 0.0, 0.0, -2.0"}) {
    BrokenFixture broken;
    broken.replace("scene_gt.json", good,
                   std::string("\"cam_R_m2c\": [") + R + "], \"cam_t_m2c\": [-7.0");
    EXPECT_TRUE(throws_input_error([&] { BopReader reader(broken.split()); },
                                   "000001/scene_gt.json",
                                   "image 0, gt 1: cam_R_m2c is not a rotation"))
        << R;
  }
  BrokenFixture reflected;  // det -1 in an image that was not flipped
  reflected.replace("scene_gt.json", good,
                    "\"cam_R_m2c\": [0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0], "
                    "\"cam_t_m2c\": [-7.0");
  EXPECT_TRUE(throws_input_error([&] { BopReader reader(reflected.split()); },
                                 "000001/scene_gt.json",
                                 "image 0, gt 1: cam_R_m2c is a reflection, not a rotation"));
}

TEST(BopBadInput, MirroredImageKeepsItsReflectedPoses) {
  BrokenFixture broken;
  broken.replace("scene_gt.json",
                 "0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, -1.0], \"cam_t_m2c\": [4.0",
                 "0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0], \"cam_t_m2c\": [4.0");
  broken.replace("scene_camera.json", "\"elev\": 35", "\"elev\": 35, \"flip_horizontal\": true");
  const BopReader reader(broken.split());
  EXPECT_DOUBLE_EQ(reader.record(1).parts[0].cam_R_m2c.determinant(), -1.0);
}

TEST(BopBadInput, GroundTruthTranslationOutsideThePhysicalRange) {
  const std::string good = "\"cam_t_m2c\": [-7.0, -5.5, 700.0]";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"[0.0, 0.0, 0.0]", "cam_t_m2c puts the part behind the camera"},
      {"[0.0, 0.0, -700.0]", "cam_t_m2c puts the part behind the camera"},
      {"[0.0, 0.0, 1e30]",
       "cam_t_m2c [0, 0, 1e+30] is farther than 100000 mm from the camera"}};
  for (const auto& [t, problem] : cases) {
    BrokenFixture broken;
    broken.replace("scene_gt.json", good, "\"cam_t_m2c\": " + t);
    EXPECT_TRUE(throws_input_error([&] { BopReader reader(broken.split()); },
                                   "000001/scene_gt.json", "image 0, gt 1: " + problem))
        << t;
  }
}

TEST(BopBadInput, CameraOutsideThePhysicalRange) {
  const std::string fx = "[1075.65091572, 0.0, 374.06888344, 0.0, 1073.90347929";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"[0.0, 0.0, 374.06888344, 0.0, 0.0", "image 0: cam_K: focal lengths fx = 0, fy = 0"},
      {"[1e308, 0.0, 374.06888344, 0.0, 1073.90347929",
       "image 0: cam_K: focal lengths fx = 1e+308"},
      {"[1075.65091572, 0.0, 1e300, 0.0, 1073.90347929", "image 0: cam_K: principal point"}};
  for (const auto& [K, problem] : cases) {
    BrokenFixture broken;
    broken.replace("scene_camera.json", fx, K);
    EXPECT_TRUE(throws_input_error([&] { BopReader reader(broken.split()); },
                                   "000001/scene_camera.json", problem))
        << K;
  }
  BrokenFixture scale;
  scale.replace("scene_camera.json", "\"depth_scale\": 0.1", "\"depth_scale\": 1e308");
  EXPECT_TRUE(throws_input_error([&] { BopReader reader(scale.split()); },
                                 "000001/scene_camera.json",
                                 "image 0: depth_scale 1e+308 is beyond 100 mm per depth unit"));
}

TEST(BopBadInput, BoxesWithANegativeSizeOrOutsideTheImage) {
  BrokenFixture negative;
  negative.replace("scene_gt_info.json", "\"bbox_visib\": [9, 7, 13, 11]",
                   "\"bbox_visib\": [9, 7, -13, 11]");
  EXPECT_TRUE(throws_input_error([&] { BopReader reader(negative.split()); },
                                 "000001/scene_gt_info.json",
                                 "image 0, gt 1: bbox_visib: [9,7,-13,11] has a negative width"));
  BrokenFixture outside;
  outside.replace("scene_gt_info.json", "\"bbox_visib\": [9, 7, 13, 11]",
                  "\"bbox_visib\": [29, 7, 13, 11]");
  const BopReader reader(outside.split());  // the image's size is known at load()
  EXPECT_TRUE(throws_input_error([&] { reader.load(0); }, "000001/scene_gt_info.json",
                                 "image 0, gt 1: bbox_visib [29, 7, 13, 11] reaches beyond the "
                                 "32x24 image"));
  BrokenFixture no_pixels;  // BOP's mark of a part without pixels stays accepted
  no_pixels.replace("scene_gt_info.json", "\"bbox_visib\": [9, 7, 13, 11]",
                    "\"bbox_visib\": [-1, -1, -1, -1]");
  EXPECT_NO_THROW(BopReader(no_pixels.split()).load(0));
}

// synth semi's pasted parts have no pose: identity and the origin, marked in the camera
// entry, are read as they are.
TEST(BopBadInput, PlaceholderPosesOfPastedImagesAreRead) {
  BrokenFixture broken;
  broken.replace("scene_gt.json", "\"cam_t_m2c\": [4.0, -2.5, 650.0]",
                 "\"cam_t_m2c\": [0.0, 0.0, 0.0]");
  EXPECT_TRUE(throws_input_error([&] { BopReader reader(broken.split()); },
                                 "000001/scene_gt.json", "image 1, gt 0: cam_t_m2c puts the part"));
  broken.replace("scene_camera.json", "\"elev\": 35", "\"elev\": 35, \"pose_unknown\": true");
  const BopReader reader(broken.split());
  EXPECT_EQ(reader.record(1).parts[0].cam_t_m2c, Eigen::Vector3d::Zero());
}
