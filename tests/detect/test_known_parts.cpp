// Known-part mode in the detector (host/detect/known_parts.h): the shipped softmax model
// on an image of the tless_synth_8 fixture keeps exactly the known classes, its scores the
// softmax over them and the background; the tiny fixture made sigmoid is plain filtering;
// the --parts list and an id the model lacks are refused naming --parts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <filesystem>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <set>
#include <string>
#include <vector>

#include "host/detect/known_parts.h"
#include "host/detect/ssd_detector.h"
#include "host/io/input_error.h"
#include "tests/common/test_support.h"
#include "tests/detect/detector_fixture.h"

namespace flexsight {
namespace {

namespace fs = std::filesystem;
using namespace testing_support;

const std::string kShippedModel = std::string(FLEXSIGHT_SOURCE_DIR) + "/models/tless-ssd/model.onnx";

BackendOptions backend(BackendKind kind) {
  BackendOptions options;
  options.kind = kind;
  return options;
}

cv::Mat fixture_scene() {
  return cv::imread(std::string(FLEXSIGHT_TEST_DATA_DIR) + "/detect/tless_synth_8/000000/rgb/000000.jpg",
                    cv::IMREAD_COLOR);
}

// A low threshold: many boxes of many classes, so that leaving classes out shows.
SsdDetectorOptions low_threshold(const KnownParts& parts = {}) {
  SsdDetectorOptions options;
  options.score_threshold = 0.02f;
  options.parts = parts;
  return options;
}

// IoU of two detections' pixel boxes (x0, y0, x1, y1).
double box_iou(const ObjectDetection& a, const ObjectDetection& b) {
  const double w = std::min(a.box[2], b.box[2]) - std::max(a.box[0], b.box[0]);
  const double h = std::min(a.box[3], b.box[3]) - std::max(a.box[1], b.box[1]);
  if (w <= 0 || h <= 0) return 0.0;
  const double area_a = double(a.box[2] - a.box[0]) * (a.box[3] - a.box[1]);
  const double area_b = double(b.box[2] - b.box[0]) * (b.box[3] - b.box[1]);
  return w * h / (area_a + area_b - w * h);
}

std::string input_error_of(const std::function<void()>& call) {
  try {
    call();
  } catch (const InputError& error) {
    return error.what();
  }
  ADD_FAILURE() << "no InputError";
  return {};
}

TEST(KnownParts, ParsesACommaListIntoAscendingIds) {
  EXPECT_EQ(parse_known_parts("12,5").obj_ids, (std::vector<int>{5, 12}));
  EXPECT_EQ(parse_known_parts("7").obj_ids, (std::vector<int>{7}));
  EXPECT_TRUE(KnownParts{}.every_part());
  EXPECT_TRUE(KnownParts{}.contains(3));
  const KnownParts parts = parse_known_parts("5,12");
  EXPECT_TRUE(parts.contains(12));
  EXPECT_FALSE(parts.contains(7));
}

TEST(KnownParts, MalformedListsNameTheOption) {
  for (const char* text : {"", ",", "5,", ",5", "5,,12", "x", "5.5", "-5", "5 ,12", "1234567890"}) {
    EXPECT_NE(input_error_of([&] { parse_known_parts(text); }).find("option --parts: expected object ids"),
              std::string::npos)
        << "'" << text << "'";
  }
  EXPECT_NE(input_error_of([&] { parse_known_parts("0"); }).find("option --parts: object ids start at 1"),
            std::string::npos);
  EXPECT_NE(input_error_of([&] { parse_known_parts("5,12,5"); }).find("option --parts: object 5 is given twice"),
            std::string::npos);
}

TEST(KnownParts, AnIdTheDetectorLacksNamesPartsAndTheModel) {
  const std::string error =
      input_error_of([&] { SsdDetector detector(tiny_ssd_model(), low_threshold(parse_known_parts("5,6"))); });
  EXPECT_NE(error.find("option --parts: object 6 is not a class of the detector " + tiny_ssd_model()),
            std::string::npos)
      << error;
}

// The shipped model is softmax: the known classes' boxes only, each scored by the softmax
// over the background and the known classes at its anchor; that can only raise a score,
// so every known-class box of the full run is still there, at least as high, unless a box
// of its class that the renormalisation lifted above it now suppresses it (NMS).
TEST(KnownParts, SoftmaxKeepsExactlyTheKnownClassesRenormalised) {
  const cv::Mat bgr = fixture_scene();
  ASSERT_FALSE(bgr.empty());
  SsdDetector every(kShippedModel, low_threshold(), backend(BackendKind::Reference));
  ASSERT_EQ(every.postprocess_params().score_function, SsdScoreFunction::Softmax);
  const std::vector<ObjectDetection> all = every.detect(bgr);
  std::map<int, int> boxes_of;  // category -> boxes in the full run
  for (const ObjectDetection& d : all) ++boxes_of[d.category_id];
  ASSERT_GE(boxes_of.size(), 4u) << "the scene should show several classes";
  // The two classes with the most boxes are the known parts.
  std::vector<std::pair<int, int>> by_count;
  for (const auto& [category, count] : boxes_of) by_count.push_back({count, category});
  std::sort(by_count.rbegin(), by_count.rend());
  const KnownParts parts{{std::min(by_count[0].second, by_count[1].second), std::max(by_count[0].second, by_count[1].second)}};

  SsdDetector known(kShippedModel, low_threshold(parts), backend(BackendKind::Reference));
  const SsdNetworkOutputs outputs = known.forward(known.preprocess(bgr));
  const std::vector<ObjectDetection> found = known.postprocess(outputs, bgr.size());
  std::set<int> found_categories;
  for (const ObjectDetection& d : found) {
    found_categories.insert(d.category_id);
    EXPECT_EQ(known.labels().at(d.class_id).category_id, d.category_id);
    // softmax over the background and the known classes at the anchor
    const float* logits = outputs.class_logits.ptr<float>(d.anchor);
    double sum = std::exp(double(logits[0]));
    for (int id : parts.obj_ids) {
      for (std::size_t c = 0; c < known.labels().size(); ++c) {
        if (known.labels()[c].category_id == id) sum += std::exp(double(logits[c + 1]));
      }
    }
    EXPECT_NEAR(d.score, std::exp(double(logits[d.class_id + 1])) / sum, 1e-5);
  }
  EXPECT_EQ(found_categories, std::set<int>(parts.obj_ids.begin(), parts.obj_ids.end()));
  for (const ObjectDetection& d : all) {
    if (!parts.contains(d.category_id)) continue;
    const bool kept = std::any_of(found.begin(), found.end(), [&](const ObjectDetection& k) {
      return k.anchor == d.anchor && k.category_id == d.category_id && k.score >= d.score - 1e-6f;
    });
    const bool suppressed = std::any_of(found.begin(), found.end(), [&](const ObjectDetection& k) {
      return k.category_id == d.category_id && k.score >= d.score && box_iou(k, d) > 0.6;
    });
    EXPECT_TRUE(kept || suppressed) << "category " << d.category_id << " at anchor " << d.anchor << " score " << d.score;
  }
  // The OpenCL path (where there is one) gives the same detections.
  SsdDetector known_auto(kShippedModel, low_threshold(parts), backend(BackendKind::Auto));
  const std::vector<ObjectDetection> found_auto = known_auto.detect(bgr);
  ASSERT_EQ(found_auto.size(), found.size());
  for (std::size_t i = 0; i < found.size(); ++i) {
    EXPECT_EQ(found_auto[i].anchor, found[i].anchor);
    EXPECT_EQ(found_auto[i].category_id, found[i].category_id);
    EXPECT_FLOAT_EQ(found_auto[i].score, found[i].score);
  }
}

// A sigmoid model's class scores are independent: known-part mode is the full run's
// detections of those classes, box for box and score for score.
TEST(KnownParts, SigmoidIsTheFullRunFilteredByClass) {
  const fs::path dir = fresh_temp_dir("KnownPartsSigmoid");
  const std::string model = copy_tiny_ssd(dir);
  write_text(dir / "model.json", "{\"score_function\": \"sigmoid\", \"input_size\": 300}\n");
  const cv::Mat bgr = cv::imread(tiny_ssd_image(), cv::IMREAD_COLOR);
  SsdDetector every(model, low_threshold(), backend(BackendKind::Reference));
  const KnownParts parts{{kTinyRedCategory}};
  SsdDetector known(model, low_threshold(parts), backend(BackendKind::Reference));
  std::vector<ObjectDetection> expected;
  std::set<int> all_categories;
  for (const ObjectDetection& d : every.detect(bgr)) {
    all_categories.insert(d.category_id);
    if (parts.contains(d.category_id)) expected.push_back(d);
  }
  ASSERT_TRUE(all_categories.count(kTinyBlueCategory)) << "the full run should find the left-out class";
  const std::vector<ObjectDetection> found = known.detect(bgr);
  ASSERT_EQ(found.size(), expected.size());
  for (std::size_t i = 0; i < found.size(); ++i) {
    EXPECT_EQ(found[i].category_id, expected[i].category_id);
    EXPECT_EQ(found[i].class_id, expected[i].class_id);
    EXPECT_EQ(found[i].anchor, expected[i].anchor);
    EXPECT_EQ(found[i].score, expected[i].score);
    for (int k = 0; k < 4; ++k) EXPECT_EQ(found[i].box[k], expected[i].box[k]);
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace flexsight
