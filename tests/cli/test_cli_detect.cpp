// flexsight detect end to end on the tiny SSD fixture: the COCO results file, the order
// and numbering of the inputs, the same bytes from the reference and the OpenCL
// post-processing, the pictures, and every bad input rejected before an output changes.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "tests/cli/cli_test_support.h"
#include "tests/detect/detector_fixture.h"

namespace {

namespace fs = std::filesystem;
using namespace flexsight::cli_test_support;
using namespace flexsight::testing_support;

class DetectCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fresh_temp_dir(std::string("DetectCli_") +
                          ::testing::UnitTest::GetInstance()->current_test_info()->name());
    json_ = (dir_ / "dets.json").string();
    png_ = (dir_ / "boxes.png").string();
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir_);
  }
  // "detect ... --model <fixture>"
  std::string detect(const std::string& arguments) const {
    return "detect " + arguments + " --model " + tiny_ssd_model() + " --device reference";
  }
  // A folder of pure-colour images (BGR) named as given.
  fs::path colour_folder(const std::vector<std::pair<std::string, cv::Scalar>>& images) const {
    const fs::path folder = dir_ / "images";
    fs::create_directories(folder);
    for (const auto& [name, bgr] : images) {
      cv::imwrite((folder / name).string(), cv::Mat(120, 160, CV_8UC3, bgr));
    }
    return folder;
  }
  fs::path dir_;
  std::string json_, png_;
};

TEST_F(DetectCli, WritesCocoResults) {
  RunResult r = run_flexsight(detect(tiny_ssd_image() + " -o " + json_), dir_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("detect: 1 image with "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("time per image (median of 1): read "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(" images/s end to end"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;  // the table only without -o

  const nlohmann::json results = nlohmann::json::parse(read_text(json_));
  ASSERT_TRUE(results.is_array());
  ASSERT_FALSE(results.empty());
  // The default post-processing (score 0.3, top-k 100, 100 detections) of the fixture.
  EXPECT_LE(results.size(), 100u);
  double previous_score = 1.0;
  for (const nlohmann::json& d : results) {
    ASSERT_EQ(d.size(), 5u) << d.dump();
    EXPECT_EQ(d["image_id"], 1);
    EXPECT_TRUE(d["category_id"] == kTinyRedCategory || d["category_id"] == kTinyBlueCategory)
        << d.dump();
    EXPECT_EQ(d["file_name"], tiny_ssd_image());
    const double score = d["score"].get<double>();
    EXPECT_GT(score, 0.3);
    EXPECT_LE(score, previous_score);  // best first
    previous_score = score;
    ASSERT_EQ(d["bbox"].size(), 4u);
    const double x = d["bbox"][0], y = d["bbox"][1], w = d["bbox"][2], h = d["bbox"][3];
    EXPECT_GE(x, 0.0);
    EXPECT_GE(y, 0.0);
    EXPECT_GT(w, 0.0);
    EXPECT_GT(h, 0.0);
    EXPECT_LE(x + w, 317.0 + 1e-3);
    EXPECT_LE(y + h, 241.0 + 1e-3);
  }
  // The best box: NumPy's best detection (expected_detections.json) in pixels, COCO style.
  const nlohmann::json expected =
      nlohmann::json::parse(read_text(tiny_ssd_dir() + "/expected_detections.json"));
  const nlohmann::json& best = expected["detections"][0];
  const nlohmann::json& first = results[0];
  EXPECT_EQ(first["category_id"],
            best["class_id"].get<int>() == 0 ? kTinyRedCategory : kTinyBlueCategory);
  EXPECT_NEAR(first["score"].get<double>(), best["score"].get<double>(), 1e-5);
  const double x0 = best["box"][0].get<double>() * 317, y0 = best["box"][1].get<double>() * 241;
  const double x1 = best["box"][2].get<double>() * 317, y1 = best["box"][3].get<double>() * 241;
  EXPECT_NEAR(first["bbox"][0].get<double>(), x0, 1e-3);
  EXPECT_NEAR(first["bbox"][1].get<double>(), y0, 1e-3);
  EXPECT_NEAR(first["bbox"][2].get<double>(), x1 - x0, 1e-3);
  EXPECT_NEAR(first["bbox"][3].get<double>(), y1 - y0, 1e-3);
}

// One tile the image's size is the whole image: the same bytes as without --tile. Smaller
// tiles overlap by a quarter tile and put every box inside the image.
TEST_F(DetectCli, TilesOfTheImagesSizeAreTheWholeImage) {
  const cv::Mat image = cv::imread(tiny_ssd_image());
  const std::string square = (dir_ / "square.png").string();
  cv::imwrite(square, image(cv::Rect(0, 0, image.rows, image.rows)));  // 241 x 241
  const std::string whole_json = (dir_ / "whole.json").string();
  RunResult whole = run_flexsight(detect(square + " --score 0.05 -o " + whole_json), dir_);
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  EXPECT_EQ(whole.err.find("tiles of"), std::string::npos) << whole.err;
  RunResult one_tile = run_flexsight(detect(square + " --score 0.05 --tile 241 -o " + json_), dir_);
  ASSERT_EQ(one_tile.exit_code, 0) << one_tile.err;
  EXPECT_NE(one_tile.err.find("tiles of 241 px, stride 180 px"), std::string::npos) << one_tile.err;
  EXPECT_FALSE(read_text(whole_json).empty());
  EXPECT_EQ(read_text(json_), read_text(whole_json));

  RunResult tiled = run_flexsight(detect(tiny_ssd_image() + " --score 0.05 --tile 100 -o " + json_), dir_);
  ASSERT_EQ(tiled.exit_code, 0) << tiled.err;
  const nlohmann::json results = nlohmann::json::parse(read_text(json_));
  ASSERT_FALSE(results.empty());
  EXPECT_NE(results.dump(), nlohmann::json::parse(read_text(whole_json)).dump());
  for (const nlohmann::json& d : results) {
    EXPECT_GE(d["bbox"][0].get<double>(), 0.0);
    EXPECT_GE(d["bbox"][1].get<double>(), 0.0);
    EXPECT_LE(d["bbox"][0].get<double>() + d["bbox"][2].get<double>(), 317.0 + 1e-3);
    EXPECT_LE(d["bbox"][1].get<double>() + d["bbox"][3].get<double>(), 241.0 + 1e-3);
  }
}

TEST_F(DetectCli, PrintsATableWithoutOutputFile) {
  RunResult r = run_flexsight(detect(tiny_ssd_image()), dir_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("image 1: " + tiny_ssd_image() + " (317x241): "), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("red_box"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("blue_box"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("green_box"), std::string::npos) << r.out;
}

// A folder's images in name order, numbered from 1, other files ignored; each pure colour
// found as its class.
TEST_F(DetectCli, AFolderIsSortedAndNumbered) {
  const fs::path folder = colour_folder(
      {{"c_blue.png", {255, 0, 0}}, {"a_red.jpg", {0, 0, 255}}, {"b_green.JPEG", {0, 255, 0}}});
  write_text(folder / "notes.txt", "not an image");
  RunResult r =
      run_flexsight(detect(folder.string() + " -o " + json_ + " --png " + png_ + " --quiet"), dir_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("detect: 3 images"), std::string::npos) << r.err;
  const nlohmann::json results = nlohmann::json::parse(read_text(json_));
  const std::pair<std::string, int> order[] = {{"a_red.jpg", kTinyRedCategory},
                                               {"b_green.JPEG", kTinyGreenCategory},
                                               {"c_blue.png", kTinyBlueCategory}};
  for (int id = 1; id <= 3; ++id) {
    const nlohmann::json* best = nullptr;
    for (const nlohmann::json& d : results) {
      if (d["image_id"] == id && (!best || d["score"] > (*best)["score"])) best = &d;
    }
    ASSERT_NE(best, nullptr) << "no detection in image " << id;
    EXPECT_EQ((*best)["file_name"], (folder / order[id - 1].first).string());
    EXPECT_EQ((*best)["category_id"], order[id - 1].second);
  }
  // Three images: a grid of 3 tiles, 320 pixels wide (+ 4-pixel gaps), 240 high.
  const cv::Mat sheet = cv::imread(png_, cv::IMREAD_UNCHANGED);
  EXPECT_EQ(sheet.cols, 3 * (320 + 4) + 4);
  EXPECT_EQ(sheet.rows, 240 + 2 * 4);
}

TEST_F(DetectCli, OneImagePictureKeepsItsSize) {
  RunResult r = run_flexsight(detect(tiny_ssd_image() + " --png " + png_), dir_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const cv::Mat picture = cv::imread(png_, cv::IMREAD_COLOR);
  const cv::Mat original = cv::imread(tiny_ssd_image(), cv::IMREAD_COLOR);
  ASSERT_EQ(picture.size(), original.size());
  EXPECT_GT(cv::norm(picture, original, cv::NORM_L1), 0.0);  // boxes drawn on it
}

// The post-processing's two paths give the same detections, so the same file.
TEST_F(DetectCli, ReferenceAndOpenClWriteTheSameBytes) {
  const fs::path folder = colour_folder({{"red.png", {0, 0, 255}}, {"mix.png", {40, 200, 90}}});
  fs::copy_file(tiny_ssd_image(), folder / "fixture.png");
  const std::string inputs = folder.string() + " --model " + tiny_ssd_model() + " --quiet";
  const std::string reference = (dir_ / "reference.json").string();
  const std::string opencl = (dir_ / "opencl.json").string();
  RunResult a =
      run_flexsight("detect " + inputs + " -o " + reference + " --device reference", dir_);
  ASSERT_EQ(a.exit_code, 0) << a.err;
  EXPECT_NE(a.err.find("post-processing on the reference path"), std::string::npos) << a.err;
  RunResult b = run_flexsight("detect " + inputs + " -o " + opencl + " --device opencl", dir_);
  ASSERT_EQ(b.exit_code, 0) << b.err;
  EXPECT_NE(b.err.find("post-processing on the OpenCL path on #"), std::string::npos) << b.err;
  const std::string reference_bytes = read_text(reference);
  EXPECT_GT(reference_bytes.size(), 1000u);
  EXPECT_EQ(reference_bytes, read_text(opencl));
}

// The network on OpenCV DNN's OpenCL layers, here on PoCL (OpenCV takes CPU devices and
// DNN runs on them only when told): the same detections as its CPU layers, up to rounding.
TEST_F(DetectCli, DnnOpenClTargetFindsWhatTheCpuFinds) {
  const std::string cpu = (dir_ / "cpu.json").string();
  RunResult a = run_flexsight(detect(tiny_ssd_image() + " -o " + cpu), dir_);
  ASSERT_EQ(a.exit_code, 0) << a.err;
  RunResult b =
      run_flexsight(detect(tiny_ssd_image() + " -o " + json_ + " --dnn-target opencl"), dir_,
                    "OPENCV_OPENCL_DEVICE=:CPU: OPENCV_DNN_OPENCL_ALLOW_ALL_DEVICES=1 ");
  ASSERT_EQ(b.exit_code, 0) << b.err;
  EXPECT_NE(b.err.find("network on OpenCV DNN (opencl, "), std::string::npos) << b.err;
  const nlohmann::json on_cpu = nlohmann::json::parse(read_text(cpu));
  const nlohmann::json on_opencl = nlohmann::json::parse(read_text(json_));
  ASSERT_EQ(on_opencl.size(), on_cpu.size());
  for (size_t i = 0; i < on_cpu.size(); ++i) {
    EXPECT_EQ(on_opencl[i]["category_id"], on_cpu[i]["category_id"]);
    EXPECT_NEAR(on_opencl[i]["score"].get<double>(), on_cpu[i]["score"].get<double>(), 1e-5);
    for (int k = 0; k < 4; ++k) {
      EXPECT_NEAR(on_opencl[i]["bbox"][k].get<double>(), on_cpu[i]["bbox"][k].get<double>(), 1e-2);
    }
  }
  // Without the permission OpenCV DNN would run on its CPU layers; the command says so.
  RunResult c =
      run_flexsight(detect(tiny_ssd_image() + " --dnn-target opencl"), dir_,
                    "OPENCV_OPENCL_DEVICE=:CPU: env -u OPENCV_DNN_OPENCL_ALLOW_ALL_DEVICES ");
  EXPECT_EQ(c.exit_code, 1);
  EXPECT_NE(c.err.find("option --dnn-target: opencl: OpenCV's OpenCL device "), std::string::npos)
      << c.err;
  EXPECT_NE(c.err.find(" is not a GPU"), std::string::npos) << c.err;
}

TEST_F(DetectCli, ParametersReachThePostprocessing) {
  RunResult r = run_flexsight(
      detect(tiny_ssd_image() + " -o " + json_ + " --max-detections 3 --score 0.9"), dir_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json results = nlohmann::json::parse(read_text(json_));
  ASSERT_EQ(results.size(), 3u);
  for (const nlohmann::json& d : results) EXPECT_GT(d["score"].get<double>(), 0.9);
}

TEST_F(DetectCli, ADefaultModelThatIsMissingSaysSo) {
  RunResult r = run_flexsight("detect " + tiny_ssd_image() + " -o " + json_, dir_,
                              "FLEXSIGHT_DETECT_MODEL=" + (dir_ / "none.onnx").string() + " ");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find((dir_ / "none.onnx").string() + ": does not exist (FLEXSIGHT_DETECT_MODEL"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(json_));
  // Without the variable the build's own default runs: the committed shipped model.
  const std::string shipped = std::string(FLEXSIGHT_SOURCE_DIR) + "/models/tless-ssd/model.onnx";
  ASSERT_TRUE(fs::exists(shipped)) << shipped;
  RunResult d = run_flexsight("detect " + tiny_ssd_image() + " -o " + json_, dir_,
                              "env -u FLEXSIGHT_DETECT_MODEL ");
  EXPECT_EQ(d.exit_code, 0) << d.err;
  ASSERT_TRUE(fs::exists(json_));
  EXPECT_TRUE(nlohmann::json::parse(read_text(json_)).is_array());
}

// Rejected runs: exit 1, a message naming the file or option, and the output paths as
// they were (files that existed keep their bytes, no temporary left behind).
struct BadDetect {
  const char* name;
  // "{dir}" stands for the test's folder, "{image}" for the fixture picture, "{model}"
  // for a copy of the fixture model in {dir}/model (whose files the setup may break).
  std::string arguments;
  std::string must_mention;
};

class DetectCliRejects : public DetectCli, public ::testing::WithParamInterface<BadDetect> {};

std::string expand(std::string text, const fs::path& dir) {
  const std::pair<std::string, std::string> names[] = {
      {"{dir}", dir.string()},
      {"{image}", tiny_ssd_image()},
      {"{model}", (dir / "model" / "model.onnx").string()}};
  for (const auto& [key, value] : names) {
    for (size_t at = text.find(key); at != std::string::npos; at = text.find(key)) {
      text.replace(at, key.size(), value);
    }
  }
  return text;
}

TEST_P(DetectCliRejects, LeavesTheOutputsAsTheyWere) {
  const BadDetect& c = GetParam();
  copy_tiny_ssd(dir_ / "model");
  const fs::path model = dir_ / "model";
  write_text(model / "anchors_short.csv", without_last_line(read_text(model / "anchors.csv")));
  write_text(model / "labels_short.txt", without_last_line(read_text(model / "labels.txt")));
  if (c.arguments.find("{dir}/short_anchors") != std::string::npos) {
    copy_tiny_ssd(dir_ / "short_anchors");
    fs::copy_file(model / "anchors_short.csv", dir_ / "short_anchors/anchors.csv",
                  fs::copy_options::overwrite_existing);
  }
  if (c.arguments.find("{dir}/short_labels") != std::string::npos) {
    copy_tiny_ssd(dir_ / "short_labels");
    fs::copy_file(model / "labels_short.txt", dir_ / "short_labels/labels.txt",
                  fs::copy_options::overwrite_existing);
  }
  fs::create_directories(dir_ / "empty");
  write_text(dir_ / "not_an_image.png", "plain text");
  // A PNG cut after 100 bytes: its signature passes the first check, decoding fails.
  write_text(dir_ / "truncated.png", read_text(tiny_ssd_image()).substr(0, 100));
  write_text(json_, "previous results\n");
  write_text(png_, "previous picture\n");

  const std::string arguments = expand(c.arguments, dir_);
  RunResult r = run_flexsight("detect " + arguments + " -o " + json_ + " --png " + png_, dir_);
  EXPECT_EQ(r.exit_code, 1) << arguments << "\n" << r.err;
  EXPECT_NE(r.err.find("flexsight detect: error: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(expand(c.must_mention, dir_)), std::string::npos) << r.err;
  EXPECT_EQ(read_text(json_), "previous results\n");
  EXPECT_EQ(read_text(png_), "previous picture\n");
  for (const auto& entry : fs::directory_iterator(dir_)) {
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos)
        << "left behind: " << entry.path();
  }
}

const BadDetect kBadDetects[] = {
    {"MissingModel", "{image} --model {dir}/none.onnx", "{dir}/none.onnx: does not exist"},
    {"AnchorsWrongCount", "{image} --model {dir}/short_anchors/model.onnx",
     "{dir}/short_anchors/anchors.csv: holds 1916 anchors, the model outputs 1917 boxes"},
    {"LabelsWrongCount", "{image} --model {dir}/short_labels/model.onnx",
     "{dir}/short_labels/labels.txt: lists 2 classes besides the background"},
    {"MissingImage", "{image} {dir}/none.png --model {model}", "{dir}/none.png: does not exist"},
    {"NotAnImage", "{image} {dir}/not_an_image.png --model {model}",
     "{dir}/not_an_image.png: is not an image OpenCV can decode"},
    {"TruncatedImage", "{image} {dir}/truncated.png --model {model}", "{dir}/truncated.png: "},
    {"EmptyFolder", "{dir}/empty --model {model}",
     "{dir}/empty: holds no .png, .jpg or .jpeg images"},
    {"NoImage", "--model {model}", "detect: no IMAGE given"},
    {"ScoreAboveOne", "{image} --model {model} --score 1.5",
     "option --score: must lie in [0, 1], got 1.5"},
    {"ScoreNaN", "{image} --model {model} --score nan",
     "option --score: expected a finite number, got 'nan'"},
    {"ScoreNotANumber", "{image} --model {model} --score high",
     "option --score: expected a number, got 'high'"},
    {"IouNegative", "{image} --model {model} --iou -0.1",
     "option --iou: must lie in [0, 1], got -0.1"},
    {"TopKBeyond32Bits", "{image} --model {model} --top-k 4294967312",
     "option --top-k: expected a whole number in 1..1024, got '4294967312'"},
    {"TopKZero", "{image} --model {model} --top-k 0",
     "option --top-k: expected a whole number in 1..1024, got '0'"},
    {"MaxDetectionsFraction", "{image} --model {model} --max-detections 2.5",
     "option --max-detections: expected a whole number in 1..100000, got '2.5'"},
    {"ThreadsNegative", "{image} --model {model} --threads -1",
     "option --threads: expected a whole number in 0..1024, got '-1'"},
    {"UnknownDnnTarget", "{image} --model {model} --dnn-target gpu",
     "option --dnn-target: expected cpu or opencl, got 'gpu'"},
    {"UnknownDevice", "{image} --model {model} --device gpu", "option --device"},
    {"UnknownOption", "{image} --model {model} --scores 0.5", "option --scores: unknown option"},
};

INSTANTIATE_TEST_SUITE_P(BadInputs, DetectCliRejects, ::testing::ValuesIn(kBadDetects),
                         [](const ::testing::TestParamInfo<BadDetect>& info) {
                           return std::string(info.param.name);
                         });

TEST_F(DetectCli, APictureWithoutAnImageExtensionIsRejectedFirst) {
  const std::string picture = (dir_ / "boxes.txt").string();
  RunResult r =
      run_flexsight(detect(tiny_ssd_image() + " -o " + json_ + " --png " + picture), dir_);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find(picture + ": cannot be written: OpenCV has no encoder for its extension"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("detect: 1 image"), std::string::npos) << "checked after loading: " << r.err;
  EXPECT_FALSE(fs::exists(json_));
}

TEST_F(DetectCli, AnOutputInAMissingFolderIsRejectedFirst) {
  RunResult r =
      run_flexsight(detect(tiny_ssd_image() + " -o " + (dir_ / "no/dets.json").string()), dir_);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find((dir_ / "no/dets.json").string() +
                       ": cannot be written: its folder does not exist"),
            std::string::npos)
      << r.err;
}

}  // namespace
