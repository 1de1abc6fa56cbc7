// The reference post-processing against a brute-force greedy NMS written plainly here
// (per class: sort, then keep each box that overlaps no kept one), on every case of
// ssd_cases.h; the behaviours each case is there for; the stages' own contracts.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <vector>

#include "fallback/detect/ssd_reference.h"
#include "host/detect/ssd_postprocess.h"
#include "tests/detect/same_detections.h"
#include "tests/detect/ssd_cases.h"

namespace flexsight {
namespace {

using testing_support::case_name;
using testing_support::make_ssd_inputs;
using testing_support::same_detections;
using testing_support::SsdCase;
using testing_support::SsdInputs;
using testing_support::SsdScene;

// Greedy NMS per class, then the best max_detections overall, without masks or ranks.
// Scores and boxes come from the reference's first two stages (their maths is tested in
// test_ssd_math.cpp), IoU from ssd_iou, so that both sides compare the same numbers.
std::vector<Detection> brute_force(const SsdInputs& in, const SsdPostprocessParams& params) {
  std::vector<float> boxes, scores;
  decode_boxes(in.encodings, in.anchors, in.anchor_count, params.box_scale, boxes);
  class_scores(in.logits, in.anchor_count, in.classes, score_function_code(params.score_function),
               scores);
  const auto box_of = [&](int anchor) {
    return SsdBox{boxes[4 * anchor], boxes[4 * anchor + 1], boxes[4 * anchor + 2],
                  boxes[4 * anchor + 3]};
  };
  std::vector<Detection> all;
  for (int c = 0; c < in.classes; ++c) {
    std::vector<Detection> candidates;
    for (int a = 0; a < in.anchor_count; ++a) {
      const float score = scores[static_cast<size_t>(c) * in.anchor_count + a];
      if (score > params.score_threshold) {
        Detection d;
        d.class_id = c;
        d.score = score;
        d.anchor = a;
        candidates.push_back(d);
      }
    }
    std::stable_sort(candidates.begin(), candidates.end(),
                     [](const Detection& x, const Detection& y) { return x.score > y.score; });
    if (static_cast<int>(candidates.size()) > params.top_k_per_class) {
      candidates.resize(params.top_k_per_class);
    }
    std::vector<Detection> kept;
    for (const Detection& candidate : candidates) {
      bool suppressed = false;
      for (const Detection& survivor : kept) {
        if (ssd_iou(box_of(survivor.anchor), box_of(candidate.anchor)) > params.iou_threshold) {
          suppressed = true;
        }
      }
      if (!suppressed) kept.push_back(candidate);
    }
    all.insert(all.end(), kept.begin(), kept.end());
  }
  std::stable_sort(all.begin(), all.end(),
                   [](const Detection& x, const Detection& y) { return x.score > y.score; });
  if (static_cast<int>(all.size()) > params.max_detections) all.resize(params.max_detections);
  for (Detection& d : all) {
    const SsdBox b = box_of(d.anchor);
    d.box[0] = b.x_min;
    d.box[1] = b.y_min;
    d.box[2] = b.x_max;
    d.box[3] = b.y_max;
  }
  return all;
}

// The detections there are when NMS suppresses nothing: each class's candidates up to
// top_k, all classes' up to max_detections.
size_t unsuppressed_count(const SsdInputs& in, const SsdPostprocessParams& params) {
  std::vector<float> scores;
  class_scores(in.logits, in.anchor_count, in.classes, score_function_code(params.score_function),
               scores);
  size_t total = 0;
  for (int c = 0; c < in.classes; ++c) {
    int count = 0;
    for (int a = 0; a < in.anchor_count; ++a) {
      count += scores[static_cast<size_t>(c) * in.anchor_count + a] > params.score_threshold;
    }
    total += std::min(count, params.top_k_per_class);
  }
  return std::min(total, static_cast<size_t>(params.max_detections));
}

class SsdNmsCases : public ::testing::TestWithParam<SsdCase> {};

TEST_P(SsdNmsCases, ReferenceEqualsBruteForceGreedyNms) {
  const SsdCase& c = GetParam();
  const SsdInputs in = make_ssd_inputs(c);
  const std::vector<Detection> found =
      ssd_postprocess_reference(in.outputs(), in.anchors, c.params);
  EXPECT_TRUE(same_detections(brute_force(in, c.params), found));

  // What the case is there for.
  switch (c.scene) {
    case SsdScene::NothingAbove:
      EXPECT_TRUE(found.empty());
      break;
    case SsdScene::IdenticalBoxes: {
      // One survivor per class that has a candidate: its best anchor.
      std::set<int> classes;
      for (const Detection& d : found) EXPECT_TRUE(classes.insert(d.class_id).second);
      EXPECT_EQ(static_cast<int>(found.size()), c.classes);
      break;
    }
    case SsdScene::DisjointBoxes:
      EXPECT_EQ(found.size(), unsuppressed_count(in, c.params))
          << "nothing suppressed: only top_k and max_detections cut";
      break;
    default:
      break;
  }
  EXPECT_LE(static_cast<int>(found.size()), c.params.max_detections);
  for (size_t i = 1; i < found.size(); ++i) {
    EXPECT_TRUE(ssd_detection_before(found[i - 1].score, found[i - 1].class_id,
                                     found[i - 1].anchor, found[i].score, found[i].class_id,
                                     found[i].anchor))
        << "detections " << i - 1 << " and " << i << " out of order";
  }
}

INSTANTIATE_TEST_SUITE_P(SsdEveryCase, SsdNmsCases, ::testing::ValuesIn(testing_support::ssd_cases()),
                         [](const ::testing::TestParamInfo<SsdCase>& info) {
                           return case_name(info.param);
                         });

TEST(SsdNms, EqualScoresKeepTheLowerAnchor) {
  // Three identical boxes with one score for one class: anchor 0 survives, whatever
  // the order they were listed in.
  SsdInputs in;
  in.anchor_count = 3;
  in.classes = 1;
  in.anchors = {0.5f, 0.5f, 0.2f, 0.2f, 0.5f, 0.5f, 0.2f, 0.2f, 0.5f, 0.5f, 0.2f, 0.2f};
  in.encodings.assign(12, 0.0f);
  in.logits = {0.0f, 1.0f, 0.0f, 1.0f, 0.0f, 1.0f};
  const std::vector<Detection> found =
      ssd_postprocess_reference(in.outputs(), in.anchors, SsdPostprocessParams());
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].anchor, 0);
  EXPECT_EQ(found[0].score, ssd_sigmoid(1.0f));
  EXPECT_NEAR(found[0].box[0], 0.4f, 1e-7f);
  EXPECT_NEAR(found[0].box[3], 0.6f, 1e-7f);
}

TEST(SsdNms, SuppressionIsPerClassAndChains) {
  // Boxes A, B, C of side 0.2, each 0.02 right of the last: IoU(A, B) = IoU(B, C) =
  // 0.036 / 0.044 = 0.818, IoU(A, C) = 0.032 / 0.048 = 0.667. The two classes rank
  // them in opposite orders and suppress only within themselves.
  SsdInputs in;
  in.anchor_count = 3;
  in.classes = 2;
  in.anchors = {0.5f, 0.30f, 0.2f, 0.2f, 0.5f, 0.32f, 0.2f, 0.2f, 0.5f, 0.34f, 0.2f, 0.2f};
  in.encodings.assign(12, 0.0f);
  in.logits = {0.0f, 3.0f, 1.0f,   // A: class 0 best, class 1 third
               0.0f, 2.0f, 2.0f,   // B
               0.0f, 1.0f, 3.0f};  // C
  SsdPostprocessParams params;
  const std::vector<Detection> found = ssd_postprocess_reference(in.outputs(), in.anchors, params);
  // Limit 0.6: class 0 keeps A, which removes B and C; class 1 keeps C, which removes B
  // and A.
  ASSERT_EQ(found.size(), 2u);
  EXPECT_EQ(found[0].class_id, 0);
  EXPECT_EQ(found[0].anchor, 0);
  EXPECT_EQ(found[1].class_id, 1);
  EXPECT_EQ(found[1].anchor, 2);
  // Limit 0.7: A-C (0.667) no longer counts. B, removed by the best box, removes
  // nothing (only survivors suppress), so both classes keep A and C.
  params.iou_threshold = 0.7f;
  const std::vector<Detection> chained =
      ssd_postprocess_reference(in.outputs(), in.anchors, params);
  ASSERT_EQ(chained.size(), 4u);
  EXPECT_EQ(chained[0].anchor, 0);  // class 0, score sigmoid(3)
  EXPECT_EQ(chained[1].anchor, 2);  // class 1, sigmoid(3): equal score, higher class
  EXPECT_EQ(chained[1].class_id, 1);
  EXPECT_EQ(chained[2].anchor, 2);  // class 0, sigmoid(1)
  EXPECT_EQ(chained[3].anchor, 0);  // class 1, sigmoid(1)
}

TEST(SsdNms, TopKCutsBeforeSuppression) {
  // Disjoint boxes, so only the limits cut: 3 candidates per class at most, 4 overall.
  const SsdCase c = testing_support::ssd_case(50, 2, SsdScene::DisjointBoxes,
                                              SsdScoreFunction::Sigmoid, 3, 4);
  const SsdInputs in = make_ssd_inputs(c);
  SsdPostprocessParams params = c.params;
  params.max_detections = 100;
  EXPECT_EQ(ssd_postprocess_reference(in.outputs(), in.anchors, params).size(), 6u);
  EXPECT_EQ(ssd_postprocess_reference(in.outputs(), in.anchors, c.params).size(), 4u);
}

TEST(SsdNms, GatherListsAnchorsInOrderAndRankSortsThem) {
  const std::vector<float> scores = {0.5f, 0.9f, 0.1f, 0.9f,   // class 0
                                     0.2f, 0.2f, 0.35f, 0.31f};  // class 1
  std::vector<int> candidates, counts, sorted;
  std::vector<float> candidate_scores;
  gather_candidates(scores, 4, 2, 0.3f, candidates, candidate_scores, counts);
  EXPECT_EQ(counts, (std::vector<int>{3, 2}));
  EXPECT_EQ(std::vector<int>(candidates.begin(), candidates.begin() + 3),
            (std::vector<int>{0, 1, 3}));
  EXPECT_EQ(std::vector<int>(candidates.begin() + 4, candidates.begin() + 6),
            (std::vector<int>{2, 3}));
  rank_candidates(candidates, candidate_scores, counts, 4, 2, 2, sorted);
  EXPECT_EQ(sorted, (std::vector<int>{1, 3, 2, 3}));
}

}  // namespace
}  // namespace flexsight
