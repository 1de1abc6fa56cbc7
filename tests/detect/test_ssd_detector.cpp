// The detector (host/detect/ssd_detector.h) on the tiny SSD fixture: OpenCV DNN's outputs
// against PyTorch's, the detections against an independent NumPy decode + NMS of them,
// the model folder's settings, and every load check naming its file.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "host/detect/detector_model.h"
#include "host/detect/ssd_anchors.h"
#include "host/detect/ssd_detector.h"
#include "host/detect/ssd_postprocess.h"
#include "host/io/input_error.h"
#include "tests/common/test_support.h"
#include "tests/detect/detector_fixture.h"

namespace flexsight {
namespace {

namespace fs = std::filesystem;
using namespace testing_support;

BackendOptions reference_path() {
  BackendOptions options;
  options.kind = BackendKind::Reference;
  return options;
}

// The post-processing of expected_detections.json (make_fixture_model.py).
SsdDetectorOptions reference_json_options() {
  SsdDetectorOptions options;
  options.score_threshold = 0.3f;
  options.iou_threshold = 0.6f;
  options.top_k_per_class = 1024;
  options.max_detections = 100;
  return options;
}

cv::Mat fixture_bgr() { return cv::imread(tiny_ssd_image(), cv::IMREAD_COLOR); }

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

std::string load_error(const std::string& model) {
  return input_error_of([&] { SsdDetector detector(model, {}, reference_path()); });
}

TEST(SsdDetector, ReadsTheFixtureFolder) {
  SsdDetector detector(tiny_ssd_model(), {}, reference_path());
  EXPECT_EQ(detector.anchor_count(), kSsdMobileNetV2AnchorCount);
  EXPECT_EQ(detector.class_count(), kTinyClasses);
  ASSERT_EQ(detector.labels().size(), 3u);
  EXPECT_EQ(detector.labels()[0].category_id, kTinyRedCategory);
  EXPECT_EQ(detector.labels()[0].name, "red_box");
  EXPECT_EQ(detector.labels()[2].category_id, kTinyBlueCategory);
  EXPECT_EQ(detector.settings().input_size, 300);
  EXPECT_EQ(detector.postprocess_params().score_function, SsdScoreFunction::Softmax);
  EXPECT_NE(detector.planned().find("reference path"), std::string::npos) << detector.planned();
}

// OpenCV DNN's forward on the C++ preprocessing against PyTorch's forward on the same
// blob (recorded by the fixture script).
TEST(SsdDetector, NetworkOutputsArePyTorchsWithin1e4) {
  SsdDetector detector(tiny_ssd_model(), {}, reference_path());
  const SsdNetworkOutputs outputs = detector.forward(detector.preprocess(fixture_bgr()));
  const std::vector<float> boxes = read_floats(tiny_ssd_dir() + "/expected_box_encodings.f32");
  const std::vector<float> logits = read_floats(tiny_ssd_dir() + "/expected_class_logits.f32");
  ASSERT_EQ(outputs.box_encodings.rows, 1917);
  ASSERT_EQ(outputs.box_encodings.cols, 4);
  ASSERT_EQ(outputs.class_logits.rows, 1917);
  ASSERT_EQ(outputs.class_logits.cols, 4);
  ASSERT_EQ(boxes.size(), 1917u * 4);
  ASSERT_EQ(logits.size(), 1917u * 4);
  double box_error = 0, logit_error = 0;
  for (size_t i = 0; i < boxes.size(); ++i) {
    box_error =
        std::max(box_error, std::abs(double(outputs.box_encodings.ptr<float>()[i]) - boxes[i]));
    logit_error =
        std::max(logit_error, std::abs(double(outputs.class_logits.ptr<float>()[i]) - logits[i]));
  }
  EXPECT_LE(box_error, 1e-4);
  EXPECT_LE(logit_error, 1e-4);
  // Not trivially equal: the logits span the range the hand-set heads give them.
  const auto [low, high] = std::minmax_element(logits.begin(), logits.end());
  EXPECT_LT(*low, -3.0f);
  EXPECT_GT(*high, 7.0f);
}

// The whole detector against expected_detections.json: NumPy's decode, softmax and NMS in
// double precision of PyTorch's outputs, written without our post-processing.
TEST(SsdDetector, DetectionsAreTheNumPyReferences) {
  SsdDetector detector(tiny_ssd_model(), reference_json_options(), reference_path());
  const cv::Mat bgr = fixture_bgr();
  const std::vector<ObjectDetection> found = detector.detect(bgr);
  const nlohmann::json expected =
      nlohmann::json::parse(read_text(tiny_ssd_dir() + "/expected_detections.json"));
  ASSERT_EQ(expected["top_k"], 1024);
  const nlohmann::json& list = expected["detections"];
  ASSERT_EQ(found.size(), list.size());
  const int categories[3] = {kTinyRedCategory, kTinyGreenCategory, kTinyBlueCategory};
  for (size_t i = 0; i < found.size(); ++i) {
    const ObjectDetection& d = found[i];
    const nlohmann::json& e = list[i];
    ASSERT_EQ(d.class_id, e["class_id"].get<int>()) << "detection " << i;
    ASSERT_EQ(d.anchor, e["anchor"].get<int>()) << "detection " << i;
    EXPECT_EQ(d.category_id, categories[d.class_id]);
    EXPECT_NEAR(d.score, e["score"].get<double>(), 1e-5) << "detection " << i;
    const double size[4] = {double(bgr.cols), double(bgr.rows), double(bgr.cols), double(bgr.rows)};
    for (int k = 0; k < 4; ++k) {
      EXPECT_NEAR(d.box[k], e["box"][k].get<double>() * size[k], 1e-3) << "detection " << i;
    }
  }
}

// detect() is the reference post-processing of its own network outputs, to the bit,
// with the model's score function, boxes scaled to the image.
TEST(SsdDetector, DetectIsThePostprocessingOfItsOwnOutputs) {
  SsdDetector detector(tiny_ssd_model(), {}, reference_path());
  const cv::Mat bgr = fixture_bgr();
  const SsdNetworkOutputs outputs = detector.forward(detector.preprocess(bgr));
  SsdPostprocessParams params;
  params.score_function = SsdScoreFunction::Softmax;
  const std::vector<Detection> expected = ssd_postprocess_reference(
      outputs.view(), read_anchor_file(tiny_ssd_dir() + "/anchors.csv", 1917), params);
  const std::vector<ObjectDetection> found = detector.detect(bgr);
  ASSERT_EQ(found.size(), expected.size());
  ASSERT_FALSE(found.empty());
  for (size_t i = 0; i < found.size(); ++i) {
    const Detection pixels = detection_in_pixels(expected[i], bgr.cols, bgr.rows);
    EXPECT_EQ(found[i].class_id, pixels.class_id);
    EXPECT_EQ(found[i].anchor, pixels.anchor);
    EXPECT_EQ(found[i].score, pixels.score);
    for (int k = 0; k < 4; ++k) EXPECT_EQ(found[i].box[k], pixels.box[k]);
  }
  // Run again on the same detector: nothing of the first image is left over.
  const std::vector<ObjectDetection> again = detector.detect(bgr);
  ASSERT_EQ(again.size(), found.size());
  for (size_t i = 0; i < found.size(); ++i) EXPECT_EQ(again[i].score, found[i].score);
}

bool inside(float x, float y, const int box[4]) {
  return x >= box[0] && x < box[2] && y >= box[1] && y < box[3];
}

// What the fixture's design predicts (make_fixture_model.py): red and blue boxes where the
// picture has them, in pixels of the 317x241 image, and no green.
TEST(SsdDetector, BoxesLieOnTheColouredRectangles) {
  SsdDetector detector(tiny_ssd_model(), {}, reference_path());
  const std::vector<ObjectDetection> found = detector.detect(fixture_bgr());
  bool red = false, blue = false;
  for (const ObjectDetection& d : found) {
    EXPECT_NE(d.category_id, kTinyGreenCategory);
    const float x = 0.5f * (d.box[0] + d.box[2]), y = 0.5f * (d.box[1] + d.box[3]);
    if (d.category_id == kTinyRedCategory) {
      EXPECT_TRUE(inside(x, y, kTinyRedBox)) << "red box centred at " << x << "," << y;
      red = true;
    }
    if (d.category_id == kTinyBlueCategory) {
      EXPECT_TRUE(inside(x, y, kTinyBlueBox)) << "blue box centred at " << x << "," << y;
      blue = true;
    }
  }
  EXPECT_TRUE(red);
  EXPECT_TRUE(blue);
}

// A pure colour everywhere: its class is the best detection.
TEST(SsdDetector, APureColourIsItsClass) {
  SsdDetector detector(tiny_ssd_model(), {}, reference_path());
  const std::pair<cv::Scalar, int> cases[] = {{{0, 0, 255}, kTinyRedCategory},
                                              {{0, 255, 0}, kTinyGreenCategory},
                                              {{255, 0, 0}, kTinyBlueCategory}};
  for (const auto& [bgr, category] : cases) {
    const std::vector<ObjectDetection> found = detector.detect(cv::Mat(97, 131, CV_8UC3, bgr));
    ASSERT_FALSE(found.empty());
    EXPECT_EQ(found[0].category_id, category);
    EXPECT_GT(found[0].score, 0.99f);
  }
  // Grey: every class at softmax 0.2 at most, below the threshold of 0.3.
  EXPECT_TRUE(detector.detect(cv::Mat(50, 50, CV_8UC3, cv::Scalar::all(128))).empty());
}

TEST(SsdDetector, SigmoidScoresWhenModelJsonSaysSo) {
  const fs::path dir = fresh_temp_dir("SsdDetectorSigmoid");
  const std::string model = copy_tiny_ssd(dir);
  write_text(dir / "model.json", "{\"score_function\": \"sigmoid\", \"input_size\": 300}\n");
  SsdDetector detector(model, {}, reference_path());
  EXPECT_EQ(detector.postprocess_params().score_function, SsdScoreFunction::Sigmoid);
  const cv::Mat bgr = fixture_bgr();
  const SsdNetworkOutputs outputs = detector.forward(detector.preprocess(bgr));
  const std::vector<ObjectDetection> found = detector.detect(bgr);
  ASSERT_FALSE(found.empty());
  for (const ObjectDetection& d : found) {
    const float logit = outputs.class_logits.at<float>(d.anchor, d.class_id + 1);
    EXPECT_NEAR(d.score, 1.0 / (1.0 + std::exp(-double(logit))), 1e-6);
  }
  fs::remove_all(dir);
}

TEST(SsdDetector, WithoutModelJsonScoresAreSoftmax) {
  const fs::path dir = fresh_temp_dir("SsdDetectorNoJson");
  const std::string model = copy_tiny_ssd(dir);
  fs::remove(dir / "model.json");
  SsdDetector detector(model, {}, reference_path());
  EXPECT_EQ(detector.postprocess_params().score_function, SsdScoreFunction::Softmax);
  EXPECT_EQ(detector.settings().input_size, 300);
  fs::remove_all(dir);
}

TEST(SsdDetector, RejectsAnImageThatIsNotBgr8) {
  SsdDetector detector(tiny_ssd_model(), {}, reference_path());
  EXPECT_NE(input_error_of([&] { detector.detect(cv::Mat()); }).find("8-bit 3-channel"),
            std::string::npos);
  EXPECT_NE(input_error_of([&] { detector.detect(cv::Mat(8, 8, CV_8UC1)); }).find("8UC1"),
            std::string::npos);
}

// Each broken model folder: an InputError naming the file at fault.
class SsdDetectorLoad : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fresh_temp_dir(
        "SsdDetectorLoad_" +
        std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    model_ = copy_tiny_ssd(dir_);
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir_);
  }
  std::string file(const char* name) const { return (dir_ / name).string(); }
  fs::path dir_;
  std::string model_;
};

TEST_F(SsdDetectorLoad, AMissingModel) {
  fs::remove(model_);
  EXPECT_EQ(load_error(model_), model_ + ": does not exist");
}

TEST_F(SsdDetectorLoad, AFileThatIsNotOnnx) {
  write_text(model_, "not a network\n");
  EXPECT_EQ(load_error(model_).rfind(model_ + ": OpenCV cannot read it as an ONNX network: ", 0),
            0u)
      << load_error(model_);
}

TEST_F(SsdDetectorLoad, AMissingOutput) {
  fs::copy_file(tiny_ssd_dir() + "/missing_output/model.onnx", model_,
                fs::copy_options::overwrite_existing);
  EXPECT_EQ(load_error(model_), model_ +
                                    ": has no output 'box_encodings' (its outputs: boxes, "
                                    "scores); the detector needs box_encodings [1, N, 4] "
                                    "and class_logits [1, N, C + 1]");
}

TEST_F(SsdDetectorLoad, AnOutputOfTheWrongShape) {
  fs::copy_file(tiny_ssd_dir() + "/wrong_box_shape/model.onnx", model_,
                fs::copy_options::overwrite_existing);
  EXPECT_EQ(load_error(model_),
            model_ + ": output box_encodings has the shape [1, 1917, 5], expected [1, N, 4]");
}

TEST_F(SsdDetectorLoad, AnchorsOneShort) {
  write_text(file("anchors.csv"), without_last_line(read_text(file("anchors.csv"))));
  EXPECT_EQ(load_error(model_),
            file("anchors.csv") + ": holds 1916 anchors, the model outputs 1917 boxes");
}

TEST_F(SsdDetectorLoad, AMissingAnchorsFile) {
  fs::remove(file("anchors.csv"));
  EXPECT_EQ(load_error(model_), file("anchors.csv") + ": does not exist");
}

TEST_F(SsdDetectorLoad, LabelsOneShort) {
  write_text(file("labels.txt"), without_last_line(read_text(file("labels.txt"))));
  EXPECT_EQ(load_error(model_), file("labels.txt") +
                                    ": lists 2 classes besides the background, the model "
                                    "outputs 4 logit columns (3 classes and the background)");
}

TEST_F(SsdDetectorLoad, LabelsOneTooMany) {
  write_text(file("labels.txt"), read_text(file("labels.txt")) + "4 11 yellow_box\n");
  EXPECT_NE(load_error(model_).find("labels.txt: lists 4 classes"), std::string::npos);
}

TEST_F(SsdDetectorLoad, MalformedLabels) {
  const std::pair<std::string, std::string> cases[] = {
      {"0 0 background\n1 5\n", "line 2: expected 'INDEX CATEGORY_ID NAME', got '1 5'"},
      {"0 0 background\n1 five red_box\n", "line 2: expected 'INDEX CATEGORY_ID NAME'"},
      {"0 0 background\n2 5 red_box\n", "line 2: expected index 1 (indices run 0, 1, 2, ..."},
      {"1 5 red_box\n", "line 1: expected index 0"},
      {"0 0 background\r\n1 5 red\r\n2 5 green\r\n",
       "line 3: category id 5 is given to two classes"},
      {"\n\n", "holds no labels"},
  };
  for (const auto& [text, message] : cases) {
    write_text(file("labels.txt"), text);
    const std::string error = load_error(model_);
    EXPECT_EQ(error.rfind(file("labels.txt") + ": ", 0), 0u) << error;
    EXPECT_NE(error.find(message), std::string::npos) << error;
  }
}

TEST_F(SsdDetectorLoad, LabelNamesMayHoldSpaces) {
  write_text(file("labels.txt"), "0 0 background\n1 5 red box\r\n\n2 7 green  box\n3 9 b\n");
  SsdDetector detector(model_, {}, reference_path());
  EXPECT_EQ(detector.labels()[0].name, "red box");
  EXPECT_EQ(detector.labels()[1].name, "green  box");
}

TEST_F(SsdDetectorLoad, BadModelJson) {
  const std::pair<std::string, std::string> cases[] = {
      {"{\"score_function\": \"tanh\"}", "\"score_function\": expected sigmoid or softmax"},
      {"{\"score_function\": 3}", "\"score_function\" must be \"softmax\" or \"sigmoid\""},
      {"{\"input_size\": 0}", "\"input_size\" must be a whole number of pixels in 1..4096"},
      {"{\"input_size\": 300.5}", "\"input_size\" must be a whole number"},
      {"{\"input_range\": [0, 1]}", "\"input_range\" [0,1] is not supported"},
      {"{\"color_order\": \"bgr\"}", "\"color_order\" \"bgr\" is not supported"},
      {"{\"box_scale\": [10, 10, 5]}", "\"box_scale\" must be 4 positive numbers"},
      {"{\"box_scale\": [10, 10, 5, 0]}", "\"box_scale\" must be 4 positive numbers"},
      {"{\"score_function\": ", "is not valid JSON"},
      {"[1, 2]", "must hold a JSON object"},
  };
  for (const auto& [text, message] : cases) {
    write_text(file("model.json"), text);
    const std::string error = load_error(model_);
    EXPECT_EQ(error.rfind(file("model.json"), 0), 0u) << error;
    EXPECT_NE(error.find(message), std::string::npos) << error;
  }
}

// An input size the network cannot take: OpenCV's failure, in our words, naming the model.
TEST_F(SsdDetectorLoad, AnInputSizeTheNetworkCannotTake) {
  write_text(file("model.json"), "{\"input_size\": 256}");
  const std::string error = load_error(model_);
  EXPECT_EQ(error.rfind(model_ + ": OpenCV DNN cannot run it on a [1, 3, 256, 256] input", 0), 0u)
      << error;
}

TEST(SsdDetectorOptions, OutOfRangeNameTheOption) {
  SsdDetectorOptions options;
  options.top_k_per_class = 2000;
  EXPECT_EQ(input_error_of([&] { SsdDetector d(tiny_ssd_model(), options, reference_path()); }),
            "option --top-k: must be in 1..1024, got 2000");
  EXPECT_EQ(input_error_of([] { parse_dnn_target("gpu"); }),
            "option --dnn-target: expected cpu or opencl, got 'gpu'");
}

}  // namespace
}  // namespace flexsight
