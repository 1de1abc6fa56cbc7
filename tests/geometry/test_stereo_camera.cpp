// Camera models: every calibration format on real files (copies of ../shared/datasets
// files in tests/data/calib) and on OpenCV's own stereoRectify output, checked against
// the formats' own triangulation formulas and cv::reprojectImageTo3D.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <opencv2/calib3d.hpp>

#include "host/geometry/depth_from_disparity.h"
#include "host/geometry/stereo_camera.h"
#include "host/geometry/stereo_rig.h"
#include "host/io/input_error.h"
#include "tests/common/test_support.h"

using namespace flexsight;
namespace fs = std::filesystem;

namespace {

std::string calib_file(const std::string& name) {
  return std::string(FLEXSIGHT_TEST_DATA_DIR) + "/calib/" + name;
}

// The message of the InputError that `read` throws, or "" when it does not throw.
template <typename Read>
std::string error_of(Read read) {
  try {
    read();
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

class OpenCvCalibration : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing_support::fresh_temp_dir(
        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    // A real rig: slightly rotated and offset cameras, rectified by OpenCV.
    const cv::Matx33d K(700, 0, 320, 0, 705, 240, 0, 0, 1);
    cv::Mat R;
    cv::Rodrigues(cv::Vec3d(0.002, 0.01, -0.003), R);
    const cv::Vec3d T(-0.12, 0.001, 0.002);
    cv::Mat R1, R2, P1, P2;
    cv::stereoRectify(K, cv::noArray(), K, cv::noArray(), cv::Size(640, 480), R, T, R1, R2, P1,
                      P2, Q_, cv::CALIB_ZERO_DISPARITY, 0);
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir_);
  }
  std::string write(const std::string& name, const cv::Mat& Q, const char* unit) {
    const std::string path = (dir_ / name).string();
    cv::FileStorage storage(path, cv::FileStorage::WRITE);
    storage << "image_size" << std::vector<int>{640, 480};
    if (!Q.empty()) storage << "Q" << Q;
    if (unit) storage << "unit" << unit;
    return path;
  }
  fs::path dir_;
  cv::Mat Q_;
};

}  // namespace

TEST(MiddleburyCamera, DepthIsBaselineTimesFocalOverDisparityPlusDoffs) {
  const std::string path = calib_file("middeval3_motorcycle_Q.txt");
  const StereoCamera camera = read_stereo_camera(path);
  EXPECT_EQ(camera.unit, "mm");
  EXPECT_EQ(camera.width, 741);
  for (double d : {7.0, 30.25, 65.0}) {
    EXPECT_NEAR(camera.depth(d), 193.001 * 999.421 / (d + 32.778), 1e-9);
    Eigen::Vector3d p;
    ASSERT_TRUE(camera.point(100, 400, d, p));
    const double z = 193.001 * 999.421 / (d + 32.778);
    EXPECT_NEAR(p.x(), (100 - 294.182) * z / 999.421, 1e-9);
    EXPECT_NEAR(p.y(), (400 - 252.932) * z / 999.421, 1e-9);
    EXPECT_NEAR(p.z(), z, 1e-9);
  }
  // At or beyond infinity there is no point.
  Eigen::Vector3d p;
  EXPECT_FALSE(camera.point(10, 10, -33.0, p));
  EXPECT_TRUE(std::isnan(camera.depth(-40)));
}

TEST(MiddleburyCamera, ResizedRigGivesTheSamePoints) {
  const StereoCamera full = read_stereo_camera(calib_file("middeval3_motorcycle_Q.txt"));
  const StereoCamera half = full.resized_to(370, 248);  // rounding drops half a pixel
  Eigen::Vector3d a, b;
  ASSERT_TRUE(full.point(300, 200, 40, a));
  ASSERT_TRUE(half.point(300 * 370.0 / 741, 200 * 370.0 / 741, 40 * 370.0 / 741, b));
  EXPECT_LT((a - b).norm(), 1e-9 * a.norm());
  const std::string error = error_of([&] { full.resized_to(741, 300); });
  EXPECT_NE(error.find("middeval3_motorcycle_Q.txt"), std::string::npos) << error;
  EXPECT_NE(error.find("not a uniform resize"), std::string::npos) << error;
}

TEST(StereoRig, MatchesTheCalibrationFileItBecomes) {
  // The simulator's default rig, as Q and back: the same cameras, baseline and doffs,
  // and the depth of a disparity is f B / (d + doffs).
  const StereoRig rig = make_stereo_rig(StereoRigSettings{});
  const StereoCamera camera = rig.stereo_camera();
  EXPECT_NEAR(camera.depth(rig.disparity(1234.0)), 1234.0, 1e-9);
  const StereoRig back = stereo_rig_from(camera, rig.left.width, rig.left.height);
  EXPECT_DOUBLE_EQ(back.left.fx, rig.left.fx);
  EXPECT_DOUBLE_EQ(back.left.cx, rig.left.cx);
  EXPECT_DOUBLE_EQ(back.left.cy, rig.left.cy);
  EXPECT_NEAR(back.right.cx, rig.right.cx, 1e-9);
  EXPECT_NEAR(back.baseline_mm, rig.baseline_mm, 1e-9);
  EXPECT_NEAR(back.doffs, rig.doffs, 1e-9);
  // The sensor planner's rig puts the image centre on pixel corners, the simulator's on
  // pixel centres; both shift the principal points by doffs / 2 each way.
  const StereoRig centred = make_centred_stereo_rig(500.0, 4000, 3000, 7000.0, 100.0, Projector{});
  EXPECT_EQ(centred.left.cx, 1950.0);
  EXPECT_EQ(centred.right.cx, 2050.0);
  EXPECT_EQ(centred.left_centre_x(), -250.0);
  EXPECT_EQ(centred.projector_in_left().x(), 250.0);
}

TEST(DepthFromDisparity, EachRuleKeepsItsPixels) {
  const StereoCamera camera = read_stereo_camera(testing_support::fixture_dir() + "/calib.txt");
  const float nan = std::numeric_limits<float>::quiet_NaN();
  // 80 * 750 / (d + 26): d = 10 gives 1666.7 mm; -26 is at infinity; -30 is behind it.
  const cv::Mat disparity = (cv::Mat_<float>(1, 5) << 10.0f, 0.0f, -20.0f, -30.0f, nan);
  const cv::Mat cloud = depth_from_disparity(disparity, camera, 1e-3, DepthRule::cloud());
  const cv::Mat pick = depth_from_disparity(disparity, camera, 1e-3, DepthRule::pick());
  const cv::Mat pose = depth_from_disparity(disparity, camera, 1e-3, DepthRule::pose_input());
  const float z10 = static_cast<float>(80.0 * 750 / 36), z0 = static_cast<float>(80.0 * 750 / 26),
              zm20 = static_cast<float>(80.0 * 750 / 6);
  EXPECT_FLOAT_EQ(cloud.at<float>(0), z10);
  EXPECT_FLOAT_EQ(cloud.at<float>(1), z0);
  EXPECT_TRUE(std::isnan(cloud.at<float>(2)));  // a negative disparity is no match
  EXPECT_TRUE(std::isnan(cloud.at<float>(4)));
  EXPECT_FLOAT_EQ(pick.at<float>(1), z0);
  EXPECT_FLOAT_EQ(pick.at<float>(2), zm20);  // pick trusts its own matcher's values
  EXPECT_EQ(pick.at<float>(3), 0.0f);        // behind infinity
  EXPECT_EQ(pick.at<float>(4), 0.0f);
  EXPECT_FLOAT_EQ(pose.at<float>(0), z10);
  EXPECT_EQ(pose.at<float>(1), 0.0f);  // a file's zero disparity is no match
  EXPECT_EQ(pose.at<float>(2), 0.0f);
  // Metres out: the same depths a thousand times smaller.
  EXPECT_FLOAT_EQ(depth_from_disparity(disparity, camera, 1.0, DepthRule::cloud()).at<float>(0),
                  static_cast<float>(80.0 * 750 / 36 / 1000));
}

TEST(MiddleburyCamera, FixtureCalibration) {
  const StereoCamera camera = read_stereo_camera(testing_support::fixture_dir() + "/calib.txt");
  EXPECT_NEAR(camera.depth(10), 80.0 * 750 / (10 + 26), 1e-9);
}

TEST(KittiCamera, DepthFromTheProjectionMatrices) {
  const StereoCamera camera = read_stereo_camera(calib_file("kitti2012_000070.txt"));
  EXPECT_EQ(camera.unit, "m");
  const double f = 718.856, baseline = 386.1448 / 718.856;
  EXPECT_NEAR(camera.depth(50), f * baseline / 50, 1e-9);
  Eigen::Vector3d p;
  ASSERT_TRUE(camera.point(607.1928 + 100, 185.2157, 50, p));
  EXPECT_NEAR(p.x(), 100 * (f * baseline / 50) / f, 1e-9);
  EXPECT_NEAR(p.y(), 0, 1e-9);
}

TEST_F(OpenCvCalibration, PointsEqualReprojectImageTo3D) {
  for (const char* name : {"stereo.yml", "stereo.xml"}) {
    const StereoCamera camera = read_stereo_camera(write(name, Q_, "m"));
    EXPECT_EQ(camera.unit, "m");
    EXPECT_EQ(camera.width, 640);
    cv::Mat disparity(48, 64, CV_32FC1);
    cv::randu(disparity, 5.0f, 80.0f);
    cv::Mat expected;
    cv::reprojectImageTo3D(disparity, expected, Q_, false, CV_32F);
    for (int y = 0; y < disparity.rows; ++y) {
      for (int x = 0; x < disparity.cols; ++x) {
        Eigen::Vector3d p;
        ASSERT_TRUE(camera.point(x, y, disparity.at<float>(y, x), p));
        const cv::Vec3f e = expected.at<cv::Vec3f>(y, x);
        ASSERT_NEAR(p.x(), e[0], 1e-5 * std::abs(e[2]));
        ASSERT_NEAR(p.y(), e[1], 1e-5 * std::abs(e[2]));
        ASSERT_NEAR(p.z(), e[2], 1e-5 * std::abs(e[2]));
      }
    }
  }
}

TEST_F(OpenCvCalibration, UnitDefaultsToMillimetres) {
  EXPECT_EQ(read_stereo_camera(write("no_unit.yml", Q_, nullptr)).unit, "mm");
}

TEST_F(OpenCvCalibration, RejectsMalformedFiles) {
  const std::string no_q = write("no_q.yml", cv::Mat(), "m");
  EXPECT_NE(error_of([&] { read_stereo_camera(no_q); }).find("has no Q matrix"), std::string::npos);
  const std::string small = write("small.yml", cv::Mat::eye(3, 3, CV_64F), "m");
  EXPECT_NE(error_of([&] { read_stereo_camera(small); }).find("expected 4x4"), std::string::npos);
  cv::Mat swapped = Q_.clone();
  swapped.at<double>(3, 2) = -swapped.at<double>(3, 2);
  const std::string swapped_path = write("swapped.yml", swapped, "m");
  EXPECT_NE(error_of([&] { read_stereo_camera(swapped_path); }).find("swapped"),
            std::string::npos);
  const std::string inch = write("inch.yml", Q_, "inch");
  EXPECT_NE(error_of([&] { read_stereo_camera(inch); }).find("unknown length unit 'inch'"),
            std::string::npos);
  const std::string garbage = (dir_ / "garbage.txt").string();
  std::ofstream(garbage) << "no calibration in here\n";
  const std::string error = error_of([&] { read_stereo_camera(garbage); });
  EXPECT_NE(error.find(garbage), std::string::npos) << error;
  EXPECT_NE(error.find("not a calibration file"), std::string::npos) << error;
  const std::string missing = (dir_ / "missing.yml").string();
  EXPECT_NE(error_of([&] { read_stereo_camera(missing); }).find(missing), std::string::npos);
  const std::string broken_yaml = (dir_ / "broken.yml").string();
  std::ofstream(broken_yaml) << "%YAML:1.0\nQ: !!opencv-matrix\n   rows: 4\n   cols: [\n";
  EXPECT_NE(error_of([&] { read_stereo_camera(broken_yaml); }).find(broken_yaml),
            std::string::npos);
}

// Found by tests/fuzz/fuzz_opencv_camera: a size that is not a number ("*4", a YAML
// alias OpenCV does not resolve) read as INT_MAX rows, and OpenCV then allocated
// INT_MAX x 4 doubles (64 GB) for a 200-byte file. The size is checked first now.
TEST_F(OpenCvCalibration, RejectsASizeThatIsNotANumberBeforeAllocating) {
  const std::string path = (dir_ / "alias_rows.yml").string();
  std::ofstream(path) << "%YAML:1.0\n---\nQ: !!opencv-matrix\n   rows: *4\n   cols: 4\n   dt: d\n"
                         "   data: [ 1., 0., 0., -99.5, 0., 1., 0., -93.5 ]\nunit: mm\n";
  const std::string error = error_of([&] { read_stereo_camera(path); });
  EXPECT_NE(error.find(path), std::string::npos) << error;
  EXPECT_NE(error.find("rows and cols must be whole numbers"), std::string::npos) << error;
  const std::string huge = (dir_ / "huge.yml").string();
  std::ofstream(huge) << "%YAML:1.0\n---\nQ: !!opencv-matrix\n   rows: 2000000000\n   cols: 4\n   dt: d\n"
                         "   data: [ 1. ]\n";
  EXPECT_NE(error_of([&] { read_stereo_camera(huge); }).find("expected 4x4"), std::string::npos);
  // A top level that is a list, not a map: OpenCV's lookup by name asserts.
  const std::string list = (dir_ / "list.yml").string();
  std::ofstream(list) << "%YAML:1.0\n---\n- Q\n- 1\n";
  EXPECT_NE(error_of([&] { read_stereo_camera(list); }).find("is not OpenCV YAML/XML of named values"),
            std::string::npos);
}

// Found by tests/fuzz/fuzz_opencv_camera: on this malformed file OpenCV's parser throws
// std::length_error, not cv::Exception, and it escaped the reader.
TEST(OpenCvCalibrationFuzzFinding, ALengthErrorInsideOpenCvIsAnInputError) {
  const std::string path = std::string(FLEXSIGHT_TEST_DATA_DIR) + "/calib/fuzz_opencv_length_error.yml";
  const std::string error = error_of([&] { read_opencv_camera(path); });
  EXPECT_NE(error.find(path), std::string::npos) << error;
  EXPECT_NE(error.find("is not valid OpenCV YAML/XML"), std::string::npos) << error;
}

// Found by tests/fuzz/fuzz_opencv_camera: Debian's OpenCV 4.6 FileStorage never returns
// on these files (tests/fuzz/known). read_opencv_camera checks a file's shape before
// OpenCV parses it and refuses them; a regression shows as this test timing out.
TEST(OpenCvCalibrationFuzzFinding, FilesThatHangOpenCvAreRefusedBeforeItParsesThem) {
  for (const char* name : {"opencv_camera_hang_1.yml", "opencv_camera_hang_2.yml",
                           "opencv_camera_hang_3.yml"}) {
    const std::string path = std::string(FLEXSIGHT_SOURCE_DIR) + "/tests/fuzz/known/" + name;
    ASSERT_TRUE(fs::is_regular_file(path)) << path;
    const std::string error = error_of([&] { read_opencv_camera(path); });
    EXPECT_EQ(error.rfind(path + ": is not valid OpenCV YAML/XML (line ", 0), 0u) << error;
    // read_stereo_camera takes them for Middlebury ("cam0") and KITTI ("P0:") files.
    EXPECT_EQ(error_of([&] { read_stereo_camera(path); }).rfind(path + ": ", 0), 0u);
  }
}

// The pre-check's rules, each on a small file; and what OpenCV itself writes (YAML and
// XML above, JSON here) still reads.
TEST_F(OpenCvCalibration, ThePreCheckRefusesWhatOpenCvDoesNotWrite) {
  const std::string good = "Q: !!opencv-matrix\n   rows: 4\n   cols: 4\n   dt: d\n"
                           "   data: [ 1., 0., 0., -99.5, 0., 1., 0., -93.5, 0., 0., 0., 750.,\n"
                           "       0., 0., 0.0125, 0. ]\nunit: mm\n";
  const auto read_text = [&](const std::string& name, const std::string& text) {
    const std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary) << text;
    return error_of([&] { read_opencv_camera(path); });
  };
  EXPECT_EQ(read_text("good.yml", "%YAML:1.0\n---\n" + good), "");
  EXPECT_EQ(read_text("good_crlf.yml", "%YAML 1.0\n# a comment: [ {\n" + good), "");
  const struct {
    const char* text;
    const char* why;
  } bad[] = {
      {"%YAML:1.5\n", "line 1: expected %YAML:1.0"},
      {"%YAML:1.0\n---%YAML:1.0\n", "line 2: a second document"},
      {"%YAML:1.0\n---\n--- x\n", "line 3: a second document"},
      {"%YAML:1.0\n%TAG ! x\n", "line 2: a directive"},
      {"%YAML:1.0\nQ: !!opencam0c{v-matrix-A\n", "line 2: a tag other than"},
      {"%YAML:1.0\nQ: !!opencv-4matrix\n", "line 2: a tag other than"},
      {"%YAML:1.0\nQ: [ 1, 2\n", "a '[' never closed"},
      {"%YAML:1.0\nQ: 1 ]\n", "line 2: an unmatched ']'"},
      {"%YAML:1.0\nQ: \"1\n", "line 2: a quote not closed"},
      {"%YAML:1.0\nQ: 1\n\tR: 2\n", "line 3: a tab in the indentation"},
      // The shortest form of opencv_camera_hang_3.yml: OpenCV's parser never returns.
      {"%YAML:1.0\n# c\n   ros: 4\nQ:\n--\n", "line 3: the first name is indented"},
      {"%YAML:1.0\nunit: m\xc3\xa9tre\n", "line 2: a byte that is not printable ASCII"},
      {"%YAML:1.0\nQ:\x01\n", "line 2: a byte that is not printable ASCII"},
      {"<?xml version=\"1.0\"?>\n<opencv_storage><Q>1</R></opencv_storage>\n", "line 2: a closing tag"},
      {"<?xml version=\"1.0\"?>\n<opencv_storage>\n<Q>1</Q>\n", "element <opencv_storage> never closed"},
      {"<?xml version=\"1.0\"?>\n<!DOCTYPE x>\n<a/>", "line 2: a DOCTYPE"},
      {"<?xml version=\"1.0\"?>\n<a/><b/>", "line 2: a second root"},
      {"{ \"Q\": [ 1, 2 }", "an unmatched '}'"},
      {"{ \"Q\": \"1 }\n", "a string not closed"},
  };
  for (const auto& c : bad) {
    const std::string error = read_text(std::string("bad") + (c.text[0] == '<' ? ".xml" : ".yml"), c.text);
    EXPECT_NE(error.find("is not valid OpenCV YAML/XML ("), std::string::npos) << c.text << "\n" << error;
    EXPECT_NE(error.find(c.why), std::string::npos) << c.text << "\n" << error;
  }
  EXPECT_NE(read_text("plain.yml", good).find("begins with neither %YAML, <?xml nor {"), std::string::npos);
  EXPECT_NE(read_text("big.yml", "%YAML:1.0\n# " + std::string(1 << 20, 'x') + "\n" + good)
                .find("too large for a calibration"),
            std::string::npos);

  const std::string json = (dir_ / "stereo.json").string();
  {
    cv::FileStorage storage(json, cv::FileStorage::WRITE);
    storage << "Q" << Q_ << "unit" << "m";
  }
  EXPECT_EQ(error_of([&] { read_opencv_camera(json); }), "");
  EXPECT_EQ(read_opencv_camera(json).unit, "m");
}
