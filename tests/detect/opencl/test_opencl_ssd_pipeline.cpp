// The whole OpenCL post-processing against ssd_postprocess_reference, byte for byte, on
// every case; runs of several shapes on one post-processor (its buffers are kept and
// reallocated); and the backend front on --device opencl.
#include <gtest/gtest.h>

#include <vector>

#include "host/detect/opencl_ssd_postprocessor.h"
#include "host/detect/ssd_postprocessor.h"
#include "tests/detect/opencl/ssd_device_fixture.h"
#include "tests/detect/same_detections.h"
#include "tests/detect/ssd_cases.h"

namespace flexsight::opencl::ssd_test {
namespace {

using testing_support::same_detections;
using testing_support::SsdCase;
using testing_support::SsdInputs;
using testing_support::SsdScene;

class SsdOpenClPipeline : public ::testing::TestWithParam<SsdCase> {};

TEST_P(SsdOpenClPipeline, GivesTheReferenceDetections) {
  const SsdCase& c = GetParam();
  const SsdInputs in = testing_support::make_ssd_inputs(c);
  OpenClSsdPostprocessor post(shared_context(), in.anchors);
  const std::vector<Detection> expected =
      ssd_postprocess_reference(in.outputs(), in.anchors, c.params);
  EXPECT_TRUE(same_detections(expected, post.run(in.outputs(), c.params)));
  EXPECT_TRUE(same_detections(expected, post.run(in.outputs(), c.params)))
      << "second run on the kept buffers";
}

INSTANTIATE_TEST_SUITE_P(SsdEveryCase, SsdOpenClPipeline,
                         ::testing::ValuesIn(testing_support::ssd_cases()),
                         [](const ::testing::TestParamInfo<SsdCase>& info) {
                           return testing_support::case_name(info.param);
                         });

TEST(SsdOpenClPostprocessor, RunsOfDifferentShapesOnOnePostprocessor) {
  // One anchor set, then other class counts, limits and score functions in turn.
  const SsdCase base = testing_support::ssd_case(1917, 23, SsdScene::Random);
  OpenClSsdPostprocessor post(shared_context(), testing_support::make_ssd_inputs(base).anchors);
  EXPECT_EQ(post.anchor_count(), 1917);
  const SsdCase shapes[] = {
      base,
      testing_support::ssd_case(1917, 2, SsdScene::Sparse, SsdScoreFunction::Softmax),
      testing_support::ssd_case(1917, 91, SsdScene::Random, SsdScoreFunction::Sigmoid, 7, 3),
      base,
  };
  for (const SsdCase& c : shapes) {
    const SsdInputs in = testing_support::make_ssd_inputs(c);
    EXPECT_TRUE(same_detections(ssd_postprocess_reference(in.outputs(), in.anchors, c.params),
                                post.run(in.outputs(), c.params)))
        << testing_support::case_name(c);
  }
}

TEST(SsdOpenClPostprocessor, BackendFrontRunsOnTheDeviceUnderOpenCl) {
  BackendOptions options;
  options.kind = BackendKind::OpenCl;
  ComputeBackend backend(options);
  const SsdCase c = testing_support::ssd_case(1917, 23, SsdScene::Sparse);
  const SsdInputs in = testing_support::make_ssd_inputs(c);
  SsdPostprocessor post(backend, in.anchors);
  EXPECT_EQ(post.planned().rfind("OpenCL path on", 0), 0u) << post.planned();
  bool on_device = false;
  const std::vector<Detection> found = post.run(in.outputs(), c.params, &on_device);
  EXPECT_TRUE(on_device);
  EXPECT_FALSE(found.empty());
  EXPECT_TRUE(
      same_detections(ssd_postprocess_reference(in.outputs(), in.anchors, c.params), found));
}

}  // namespace
}  // namespace flexsight::opencl::ssd_test
