// Every detection kernel against its reference function, byte for byte, on every case
// of tests/detect/ssd_cases.h: each stage gets the reference's inputs, so a difference
// points at the stage that makes it. Also: the candidates' order out of
// gather_candidates (atomic, any order) does not reach rank_candidates' output.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include "fallback/detect/ssd_reference.h"
#include "tests/detect/opencl/ssd_device_fixture.h"
#include "tests/detect/ssd_cases.h"

namespace flexsight::opencl::ssd_test {
namespace {

using testing_support::SsdCase;
using testing_support::SsdInputs;

// The reference chain of one case: every stage's output.
struct ReferenceChain {
  int n = 0, classes = 0, top_k = 0, words = 0, max_detections = 0;
  std::vector<float> boxes, scores, candidate_scores;
  std::vector<int> candidates, counts, sorted, kept, kept_counts, record_count;
  std::vector<std::uint32_t> mask;
  std::vector<SsdDetectionRecord> records;

  ReferenceChain(const SsdInputs& in, const SsdPostprocessParams& p)
      : n(in.anchor_count), classes(in.classes), top_k(p.top_k_per_class),
        words(SSD_MASK_WORDS(p.top_k_per_class)), max_detections(p.max_detections) {
    decode_boxes(in.encodings, in.anchors, n, p.box_scale, boxes);
    class_scores(in.logits, n, classes, score_function_code(p.score_function), scores);
    gather_candidates(scores, n, classes, p.score_threshold, candidates, candidate_scores, counts);
    rank_candidates(candidates, candidate_scores, counts, n, classes, top_k, sorted);
    iou_mask(boxes, sorted, counts, classes, top_k, p.iou_threshold, mask);
    nms_scan(mask, sorted, counts, classes, top_k, kept, kept_counts);
    rank_detections(scores, boxes, kept, kept_counts, n, classes, top_k, max_detections, records,
                    record_count);
  }
};

// Class c's (anchor, score) candidates in anchor order.
std::vector<std::pair<int, float>> class_candidates(const std::vector<int>& candidates,
                                                    const std::vector<float>& scores,
                                                    int anchor_count, int c, int count) {
  std::vector<std::pair<int, float>> list;
  for (int i = 0; i < count; ++i) {
    const size_t at = static_cast<size_t>(c) * anchor_count + i;
    list.emplace_back(candidates[at], scores[at]);
  }
  std::sort(list.begin(), list.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  return list;
}

// The ranked prefix of each class (slots past min(count, top_k) are not written).
::testing::AssertionResult same_class_prefixes(const std::vector<int>& expected,
                                               const std::vector<int>& actual,
                                               const std::vector<int>& counts, int top_k) {
  for (size_t c = 0; c < counts.size(); ++c) {
    const auto result =
        same_bytes(expected, actual, c * top_k, std::min(counts[c], top_k));
    if (!result) return ::testing::AssertionFailure() << "class " << c << ": " << result.message();
  }
  return ::testing::AssertionSuccess();
}

class SsdOpenClStages : public ::testing::TestWithParam<SsdCase> {};

TEST_P(SsdOpenClStages, EveryStageGivesTheReferenceBytes) {
  const SsdCase& c = GetParam();
  const SsdPostprocessParams& p = c.params;
  const SsdInputs in = testing_support::make_ssd_inputs(c);
  const ReferenceChain ref(in, p);
  const int n = ref.n, classes = ref.classes, top_k = ref.top_k;
  const size_t per_class = static_cast<size_t>(classes) * n;
  const size_t ranked = static_cast<size_t>(classes) * top_k;
  OpenClSsdStages& stages = ssd_stages();

  Buffer<float> boxes = guarded_output<float>(4 * static_cast<size_t>(n), "boxes");
  stages.decode_boxes(guarded(in.encodings, "encodings"), guarded(in.anchors, "anchors"), n,
                      p.box_scale, boxes);
  EXPECT_TRUE(same_bytes(ref.boxes, read_checked(boxes, ref.boxes.size()))) << "decode_boxes";

  Buffer<float> scores = guarded_output<float>(per_class, "scores");
  stages.class_scores(guarded(in.logits, "logits"), n, classes,
                      score_function_code(p.score_function), scores);
  EXPECT_TRUE(same_bytes(ref.scores, read_checked(scores, per_class))) << "class_scores";

  // gather_candidates: the same counts, and per class the same (anchor, score) set.
  Buffer<int> candidates = guarded_output<int>(per_class, "candidates");
  Buffer<float> candidate_scores = guarded_output<float>(per_class, "candidate scores");
  Buffer<int> counts = guarded_output<int>(classes, "counts");
  stages.gather_candidates(guarded(ref.scores, "scores"), n, classes, p.score_threshold,
                           candidates, candidate_scores, counts);
  const std::vector<int> device_counts = read_checked(counts, classes);
  ASSERT_EQ(device_counts, ref.counts) << "gather_candidates";
  const std::vector<int> device_candidates = read_checked(candidates, per_class);
  const std::vector<float> device_candidate_scores = read_checked(candidate_scores, per_class);
  for (int k = 0; k < classes; ++k) {
    ASSERT_EQ(class_candidates(device_candidates, device_candidate_scores, n, k, ref.counts[k]),
              class_candidates(ref.candidates, ref.candidate_scores, n, k, ref.counts[k]))
        << "gather_candidates, class " << k;
  }

  // rank_candidates from the reference's list (anchor order), from the device's (any
  // order) and from a shuffled one: one result.
  std::vector<int> shuffled = ref.candidates;
  std::vector<float> shuffled_scores = ref.candidate_scores;
  std::mt19937 rng(c.seed);
  for (int k = 0; k < classes; ++k) {
    const size_t base = static_cast<size_t>(k) * n;
    for (int i = ref.counts[k] - 1; i > 0; --i) {
      const int j = static_cast<int>(rng() % static_cast<unsigned>(i + 1));
      std::swap(shuffled[base + i], shuffled[base + j]);
      std::swap(shuffled_scores[base + i], shuffled_scores[base + j]);
    }
  }
  const std::pair<std::vector<int>, std::vector<float>> lists[] = {
      {ref.candidates, ref.candidate_scores},
      {device_candidates, device_candidate_scores},
      {shuffled, shuffled_scores}};
  const char* const list_names[] = {"reference order", "device order", "shuffled"};
  for (int l = 0; l < 3; ++l) {
    Buffer<int> sorted = guarded_output<int>(ranked, "sorted");
    stages.rank_candidates(guarded(lists[l].first, "candidates"),
                           guarded(lists[l].second, "candidate scores"),
                           guarded(ref.counts, "counts"), n, classes, top_k, sorted);
    EXPECT_TRUE(same_class_prefixes(ref.sorted, read_checked(sorted, ranked), ref.counts, top_k))
        << "rank_candidates from the candidates in " << list_names[l];
  }

  Buffer<std::uint32_t> mask = guarded_output<std::uint32_t>(ref.mask.size(), "mask");
  stages.iou_mask(guarded(ref.boxes, "boxes"), guarded(ref.sorted, "sorted"),
                  guarded(ref.counts, "counts"), classes, top_k, p.iou_threshold, mask);
  EXPECT_TRUE(same_bytes(ref.mask, read_checked(mask, ref.mask.size()))) << "iou_mask";

  Buffer<int> kept = guarded_output<int>(ranked, "kept");
  Buffer<int> kept_counts = guarded_output<int>(classes, "kept counts");
  stages.nms_scan(guarded(ref.mask, "mask"), guarded(ref.sorted, "sorted"),
                  guarded(ref.counts, "counts"), classes, top_k, kept, kept_counts);
  EXPECT_EQ(read_checked(kept_counts, classes), ref.kept_counts) << "nms_scan";
  EXPECT_TRUE(same_class_prefixes(ref.kept, read_checked(kept, ranked), ref.kept_counts, top_k))
      << "nms_scan";

  Buffer<SsdDetectionRecord> records =
      guarded_output<SsdDetectionRecord>(ref.max_detections, "records");
  Buffer<int> record_count = guarded_output<int>(1, "record count");
  stages.rank_detections(guarded(ref.scores, "scores"), guarded(ref.boxes, "boxes"),
                         guarded(ref.kept, "kept"), guarded(ref.kept_counts, "kept counts"), n,
                         classes, top_k, ref.max_detections, records, record_count);
  ASSERT_EQ(read_checked(record_count, 1), ref.record_count) << "rank_detections";
  EXPECT_TRUE(same_bytes(ref.records, read_checked(records, ref.max_detections), 0,
                         ref.record_count[0]))
      << "rank_detections";
}

INSTANTIATE_TEST_SUITE_P(SsdEveryCase, SsdOpenClStages,
                         ::testing::ValuesIn(testing_support::ssd_cases()),
                         [](const ::testing::TestParamInfo<SsdCase>& info) {
                           return testing_support::case_name(info.param);
                         });

}  // namespace
}  // namespace flexsight::opencl::ssd_test
