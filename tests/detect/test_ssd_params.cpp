// Parameter and input checks (InputError naming the option or input), the backend
// front's reference path, and the conversion to pixels.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "host/detect/ssd_postprocess.h"
#include "host/detect/ssd_postprocessor.h"
#include "host/io/input_error.h"
#include "tests/detect/same_detections.h"
#include "tests/detect/ssd_cases.h"

namespace flexsight {
namespace {

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

std::string check_error(const SsdPostprocessParams& params) {
  return input_error_of([&] { params.check(); });
}

TEST(SsdParams, DefaultsPass) { EXPECT_NO_THROW(SsdPostprocessParams().check()); }

TEST(SsdParams, ThresholdsOutsideTheUnitIntervalNameTheOption) {
  SsdPostprocessParams params;
  params.score_threshold = 1.5f;
  EXPECT_EQ(check_error(params), "option --score-threshold: must lie in [0, 1], got 1.5");
  params.score_threshold = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(check_error(params).rfind("option --score-threshold: must lie in [0, 1]", 0), 0u);
  params = SsdPostprocessParams();
  params.iou_threshold = -0.1f;
  EXPECT_EQ(check_error(params), "option --iou-threshold: must lie in [0, 1], got -0.1");
  params.iou_threshold = 0.0f;  // the ends are allowed: 0 keeps one box per cluster
  EXPECT_NO_THROW(params.check());
  params.iou_threshold = 1.0f;
  EXPECT_NO_THROW(params.check());
}

TEST(SsdParams, LimitsNameTheOption) {
  SsdPostprocessParams params;
  params.top_k_per_class = 0;
  EXPECT_EQ(check_error(params), "option --top-k: must be in 1..1024, got 0");
  params.top_k_per_class = 1025;
  EXPECT_EQ(check_error(params), "option --top-k: must be in 1..1024, got 1025");
  params = SsdPostprocessParams();
  params.max_detections = 0;
  EXPECT_EQ(check_error(params), "option --max-detections: must be at least 1, got 0");
  params = SsdPostprocessParams();
  params.box_scale.h = 0.0f;
  EXPECT_EQ(check_error(params),
            "option --box-scale: scale factors must be positive, got 10,10,0,5");
}

TEST(SsdParams, ScoreFunctionNames) {
  EXPECT_EQ(parse_score_function("sigmoid"), SsdScoreFunction::Sigmoid);
  EXPECT_EQ(parse_score_function("softmax"), SsdScoreFunction::Softmax);
  EXPECT_EQ(input_error_of([] { parse_score_function("relu"); }),
            "option --score-function: expected sigmoid or softmax, got 'relu'");
}

TEST(SsdParams, InputsThatDoNotFitTheAnchorsAreRefusedBeforeWork) {
  const auto c = testing_support::ssd_case(1917, 23, testing_support::SsdScene::Random);
  const testing_support::SsdInputs in = testing_support::make_ssd_inputs(c);
  std::vector<float> short_anchors(in.anchors.begin(), in.anchors.end() - 4);
  EXPECT_EQ(input_error_of([&] { ssd_postprocess_reference(in.outputs(), short_anchors, c.params); }),
            "anchors: there are 1916 anchors, the model outputs 1917 boxes");
  SsdOutputs no_logits = in.outputs();
  no_logits.class_logits = nullptr;
  EXPECT_EQ(input_error_of([&] { ssd_postprocess_reference(no_logits, in.anchors, c.params); }),
            "SSD outputs: the box encodings or class logits are missing");
  SsdOutputs no_classes = in.outputs();
  no_classes.classes = 0;
  EXPECT_NE(input_error_of([&] { ssd_postprocess_reference(no_classes, in.anchors, c.params); })
                .find("at least one anchor and one foreground class"),
            std::string::npos);
  SsdPostprocessParams bad = c.params;
  bad.score_threshold = 2.0f;
  EXPECT_EQ(input_error_of([&] { ssd_postprocess_reference(in.outputs(), in.anchors, bad); })
                .rfind("option --score-threshold", 0),
            0u);
}

TEST(SsdPostprocessorReference, GivesTheReferenceDetections) {
  BackendOptions options;
  options.kind = BackendKind::Reference;
  ComputeBackend backend(options);
  const auto c = testing_support::ssd_case(1917, 23, testing_support::SsdScene::Sparse);
  const testing_support::SsdInputs in = testing_support::make_ssd_inputs(c);
  SsdPostprocessor post(backend, in.anchors);
  EXPECT_EQ(post.planned(), "reference path");
  bool on_device = true;
  const std::vector<Detection> found = post.run(in.outputs(), c.params, &on_device);
  EXPECT_FALSE(on_device);
  EXPECT_FALSE(found.empty()) << "the sparse scene has objects";
  EXPECT_TRUE(testing_support::same_detections(
      ssd_postprocess_reference(in.outputs(), in.anchors, c.params), found));
  EXPECT_EQ(input_error_of([&] { SsdPostprocessor(backend, {0.5f, 0.5f, 0.1f}); }),
            "anchors: need 4 floats per anchor, got 3 floats");
}

TEST(SsdDetection, InPixelsScalesXByWidthAndYByHeight) {
  Detection d;
  d.box[0] = 0.25f;
  d.box[1] = 0.5f;
  d.box[2] = 0.75f;
  d.box[3] = 1.0f;
  const Detection p = detection_in_pixels(d, 640, 480);
  EXPECT_EQ(p.box[0], 160.0f);
  EXPECT_EQ(p.box[1], 240.0f);
  EXPECT_EQ(p.box[2], 480.0f);
  EXPECT_EQ(p.box[3], 480.0f);
}

}  // namespace
}  // namespace flexsight
