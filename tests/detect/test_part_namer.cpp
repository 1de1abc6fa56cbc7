// The naming stage (host/detect/part_namer.h): the shipped namer names the parts of a
// fixture image rendered by `flexsight synth full` (held-out backgrounds), and every bad
// model folder is an InputError naming its file.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "host/detect/detector_model.h"
#include "host/detect/part_namer.h"
#include "host/io/input_error.h"
#include "tests/common/test_support.h"

namespace flexsight {
namespace {

namespace fs = std::filesystem;

const std::string kNamer = std::string(FLEXSIGHT_SOURCE_DIR) + "/models/tless-namer/model.onnx";
const std::string kDetector = std::string(FLEXSIGHT_SOURCE_DIR) + "/models/tless-ssd/model.onnx";
const std::string kFixture = std::string(FLEXSIGHT_TEST_DATA_DIR) + "/detect/namer";

template <class Call>
std::string input_error_of(Call call) {
  try {
    call();
  } catch (const InputError& error) {
    return error.what();
  }
  ADD_FAILURE() << "no InputError";
  return {};
}

// A copy of the shipped namer's folder in a fresh directory, to spoil one file of.
fs::path namer_copy(const std::string& name) {
  const fs::path dir = testing_support::fresh_temp_dir(name);
  for (const char* file : {"model.onnx", "labels.txt", "model.json"}) {
    fs::copy_file(fs::path(kNamer).parent_path() / file, dir / file);
  }
  return dir;
}

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
}

TEST(PartNamer, NamesThePartsOfAHeldOutRender) {
  PartNamer namer(kNamer);
  const nlohmann::json parts = nlohmann::json::parse(std::ifstream(kFixture + "/parts.json"));
  const cv::Mat bgr = cv::imread(kFixture + "/" + parts["image"].get<std::string>(), cv::IMREAD_COLOR);
  ASSERT_FALSE(bgr.empty());
  ASSERT_GE(parts["parts"].size(), 2u);
  for (const auto& part : parts["parts"]) {
    const std::vector<float> xywh = part["bbox"].get<std::vector<float>>();
    const float box[4] = {xywh[0], xywh[1], xywh[0] + xywh[2], xywh[1] + xywh[3]};
    const std::vector<float> p = namer.name(bgr, box);
    ASSERT_EQ(p.size(), namer.labels().size());
    double sum = 0.0;
    for (float v : p) sum += v;
    EXPECT_NEAR(sum, 1.0, 1e-4);
    const int best = static_cast<int>(std::max_element(p.begin(), p.end()) - p.begin());
    EXPECT_EQ(namer.labels()[best].category_id, part["obj_id"].get<int>()) << "box at " << xywh[0] << ", " << xywh[1];
  }
}

TEST(PartNamer, CropIsTheSquareAroundTheBoxWithItsMargin) {
  PartNamer namer(kNamer);
  const int s = namer.settings().input_size;
  // A white 20x10 bar on black: with the margin the crop's side is 20 x 1.3 = 26, so the
  // bar spans 20/26 of the crop's width and 10/26 of its height, centred.
  cv::Mat grey(100, 100, CV_8UC1, cv::Scalar(0));
  grey(cv::Rect(40, 45, 20, 10)).setTo(255);
  const float box[4] = {40, 45, 60, 55};
  const cv::Mat crop = namer.crop(grey, box);
  ASSERT_EQ(crop.size(), cv::Size(s, s));
  const double white = cv::sum(crop)[0] / 255.0;
  EXPECT_NEAR(white / (s * s), 200.0 / (26.0 * 26.0), 0.02);
  EXPECT_EQ(crop.at<uchar>(s / 2, s / 2), 255);
  EXPECT_EQ(crop.at<uchar>(1, 1), 0);
  // Beyond the image's edge the edge's pixels are repeated, as in the training crops.
  const float corner[4] = {-5, -5, 15, 15};
  grey.setTo(90);
  const cv::Mat edge = namer.crop(grey, corner);
  EXPECT_EQ(cv::countNonZero(edge != 90), 0);
}

TEST(PartNamer, NamesTheDetectorsParts) {
  PartNamer namer(kNamer);
  EXPECT_NO_THROW(namer.require_same_parts(read_detector_labels(detector_files(kDetector).labels), kDetector));
  std::vector<DetectorLabel> fewer = read_detector_labels(detector_files(kDetector).labels);
  fewer.pop_back();
  const std::string error = input_error_of([&] { namer.require_same_parts(fewer, kDetector); });
  EXPECT_NE(error.find("labels.txt"), std::string::npos) << error;
  EXPECT_NE(error.find("other parts"), std::string::npos) << error;
}

TEST(PartNamer, BadModelFoldersNameTheirFile) {
  EXPECT_NE(input_error_of([] { PartNamer("/nonexistent/model.onnx"); }).find("/nonexistent/model.onnx"),
            std::string::npos);

  fs::path dir = namer_copy("namer_truncated");
  const std::uintmax_t size = fs::file_size(dir / "model.onnx");
  fs::resize_file(dir / "model.onnx", size / 2);
  std::string error = input_error_of([&] { PartNamer((dir / "model.onnx").string()); });
  EXPECT_NE(error.find((dir / "model.onnx").string()), std::string::npos) << error;

  dir = namer_copy("namer_other_parts");
  write_text(dir / "labels.txt", "0 0 background\n1 2 obj_02\n2 4 obj_04\n");
  error = input_error_of([&] { PartNamer((dir / "model.onnx").string()); });
  EXPECT_NE(error.find((dir / "labels.txt").string()), std::string::npos) << error;

  dir = namer_copy("namer_detector_json");
  write_text(dir / "model.json", R"({"score_function": "softmax", "input_size": 300})");
  error = input_error_of([&] { PartNamer((dir / "model.onnx").string()); });
  EXPECT_NE(error.find((dir / "model.json").string()), std::string::npos) << error;
  EXPECT_NE(error.find("naming"), std::string::npos) << error;

  // The detector's folder is not a namer's.
  error = input_error_of([] { PartNamer{kDetector}; });
  EXPECT_NE(error.find("model.json"), std::string::npos) << error;
}

TEST(PartNamer, RefusesAnImageOfAnotherType) {
  PartNamer namer(kNamer);
  const float box[4] = {0, 0, 10, 10};
  const std::string error = input_error_of([&] { namer.name(cv::Mat(20, 20, CV_8UC1), box); });
  EXPECT_NE(error.find("namer input"), std::string::npos) << error;
}

}  // namespace
}  // namespace flexsight
