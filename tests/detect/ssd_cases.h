#pragma once
// The inputs of SSD post-processing that the detect tests and benchmarks share: each
// case described once (anchor count, classes, what the scores and boxes look like,
// parameters), its inputs made from a fixed seed. No GoogleTest here.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <ostream>
#include <random>
#include <string>
#include <vector>

#include "host/detect/detection.h"
#include "host/detect/ssd_anchors.h"
#include "host/detect/ssd_params.h"

namespace flexsight::testing_support {

enum class SsdScene {
  Random,          // boxes jittered around their anchors, logits uniform in [-4, 2]
  Sparse,          // as a trained detector: low scores but a few clusters of boxes
  Ties,            // logits from {-1, 0, 1}, boxes equal to anchors: many equal scores
  IdenticalBoxes,  // every box the same: one survivor per class
  DisjointBoxes,   // no two boxes overlap: every candidate survives NMS
  NothingAbove,    // no score above the threshold: no detections
  Extreme,         // inf, NaN and huge encodings and logits
};

inline const char* scene_name(SsdScene scene) {
  switch (scene) {
    case SsdScene::Random: return "Random";
    case SsdScene::Sparse: return "Sparse";
    case SsdScene::Ties: return "Ties";
    case SsdScene::IdenticalBoxes: return "IdenticalBoxes";
    case SsdScene::DisjointBoxes: return "DisjointBoxes";
    case SsdScene::NothingAbove: return "NothingAbove";
    case SsdScene::Extreme: return "Extreme";
  }
  return "?";
}

struct SsdCase {
  int anchors = kSsdMobileNetV2AnchorCount;  // 1917: the TF OD API's ssd_mobilenet_v2 set
  int classes = 24;
  SsdScene scene = SsdScene::Random;
  SsdPostprocessParams params;
  std::uint32_t seed = 1;
};

inline std::string case_name(const SsdCase& c) {
  std::string name = std::string(scene_name(c.scene)) + "_" + std::to_string(c.anchors) + "x" +
                     std::to_string(c.classes) + "_" + score_function_name(c.params.score_function);
  if (c.params.top_k_per_class != SsdPostprocessParams().top_k_per_class) {
    name += "_top" + std::to_string(c.params.top_k_per_class);
  }
  if (c.params.max_detections != SsdPostprocessParams().max_detections) {
    name += "_max" + std::to_string(c.params.max_detections);
  }
  return name;
}

// gtest prints a failing case by its name (found by argument-dependent lookup).
inline void PrintTo(const SsdCase& c, std::ostream* out) { *out << case_name(c); }

// One image's network outputs with the anchors they refer to.
struct SsdInputs {
  int anchor_count = 0;
  int classes = 0;
  std::vector<float> anchors;    // N x 4
  std::vector<float> encodings;  // N x 4
  std::vector<float> logits;     // N x (classes + 1)
  SsdOutputs outputs() const {
    return {encodings.data(), logits.data(), anchor_count, classes};
  }
};

inline SsdCase ssd_case(int anchors, int classes, SsdScene scene,
                        SsdScoreFunction function = SsdScoreFunction::Sigmoid, int top_k = 100,
                        int max_detections = 100) {
  SsdCase c;
  c.anchors = anchors;
  c.classes = classes;
  c.scene = scene;
  c.params.score_function = function;
  c.params.top_k_per_class = top_k;
  c.params.max_detections = max_detections;
  c.seed = static_cast<std::uint32_t>(anchors * 131 + classes * 7 + static_cast<int>(scene));
  return c;
}

inline SsdInputs make_ssd_inputs(const SsdCase& c) {
  std::mt19937 rng(c.seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::normal_distribution<float> normal(0.0f, 1.0f);
  const int n = c.anchors;
  const int columns = c.classes + 1;
  SsdInputs in;
  in.anchor_count = n;
  in.classes = c.classes;
  in.encodings.assign(4 * static_cast<size_t>(n), 0.0f);
  in.logits.assign(static_cast<size_t>(n) * columns, 0.0f);

  // Anchors: the real set for 1917, else random boxes; a grid of small disjoint boxes
  // or one box repeated for the scenes that need them.
  if (c.scene == SsdScene::DisjointBoxes) {
    const int side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
    for (int a = 0; a < n; ++a) {
      const float cell = 1.0f / static_cast<float>(side);
      in.anchors.insert(in.anchors.end(), {(static_cast<float>(a / side) + 0.5f) * cell,
                                           (static_cast<float>(a % side) + 0.5f) * cell,
                                           0.5f * cell, 0.5f * cell});
    }
  } else if (c.scene == SsdScene::IdenticalBoxes) {
    for (int a = 0; a < n; ++a) in.anchors.insert(in.anchors.end(), {0.5f, 0.5f, 0.3f, 0.3f});
  } else if (n == kSsdMobileNetV2AnchorCount) {
    in.anchors = generate_ssd_anchors();
  } else {
    for (int a = 0; a < n; ++a) {
      in.anchors.insert(in.anchors.end(), {unit(rng), unit(rng), 0.05f + 0.45f * unit(rng),
                                           0.05f + 0.45f * unit(rng)});
    }
  }

  switch (c.scene) {
    case SsdScene::Random:
      for (float& e : in.encodings) e = normal(rng);
      for (float& l : in.logits) l = -4.0f + 6.0f * unit(rng);
      break;
    case SsdScene::Sparse: {
      // Background likely, every class unlikely (under a sigmoid and a softmax alike)...
      for (float& e : in.encodings) e = 0.5f * normal(rng);
      for (int a = 0; a < n; ++a) {
        for (int k = 0; k < columns; ++k) {
          in.logits[static_cast<size_t>(a) * columns + k] =
              k == 0 ? 3.0f + normal(rng) : -6.0f + normal(rng);
        }
      }
      // ... but for ten objects, each a run of consecutive anchors (neighbouring cells
      // and shapes of one layer) scoring high for one class.
      for (int object = 0; object < 10; ++object) {
        const int first = static_cast<int>(unit(rng) * static_cast<float>(n)) % n;
        const int c_object = static_cast<int>(unit(rng) * static_cast<float>(c.classes)) % c.classes;
        for (int a = first; a < std::min(n, first + 30); ++a) {
          in.logits[static_cast<size_t>(a) * columns + 1 + c_object] = 4.0f + 1.5f * normal(rng);
        }
      }
      break;
    }
    case SsdScene::Ties:
      for (float& l : in.logits) l = static_cast<float>(static_cast<int>(unit(rng) * 3.0f) % 3 - 1);
      break;
    case SsdScene::IdenticalBoxes:
    case SsdScene::DisjointBoxes:
      for (float& l : in.logits) l = -1.0f + 4.0f * unit(rng);
      break;
    case SsdScene::NothingAbove:
      // Low for every class under a sigmoid; the background takes all under a softmax.
      for (int a = 0; a < n; ++a) {
        for (int k = 0; k < columns; ++k) {
          in.logits[static_cast<size_t>(a) * columns + k] = k == 0 ? 10.0f : -10.0f;
        }
      }
      break;
    case SsdScene::Extreme: {
      const float specials[] = {std::numeric_limits<float>::infinity(),
                                -std::numeric_limits<float>::infinity(),
                                std::numeric_limits<float>::quiet_NaN(), 1e30f, -1e30f, 88.5f,
                                -87.5f, 0.0f};
      for (float& e : in.encodings) {
        e = unit(rng) < 0.2f ? specials[static_cast<int>(unit(rng) * 8.0f) % 8] : 3.0f * normal(rng);
      }
      for (float& l : in.logits) {
        l = unit(rng) < 0.2f ? specials[static_cast<int>(unit(rng) * 8.0f) % 8]
                             : -4.0f + 6.0f * unit(rng);
      }
      break;
    }
  }
  return in;
}

// The cases both paths are compared on: the real anchor set with the foreground class
// counts a detector has (1: one part; 23: the T-LESS parts, 24 logit columns with the
// background; 90: COCO's), awkward
// anchor counts (not multiples of any work group), equal scores, all and none
// suppressed, nothing detected, inf/NaN, and the limits top_k and max_detections cut.
inline std::vector<SsdCase> ssd_cases() {
  using S = SsdScene;
  const auto softmax = SsdScoreFunction::Softmax;
  const auto sigmoid = SsdScoreFunction::Sigmoid;
  std::vector<SsdCase> cases;
  for (int classes : {1, 2, 23, 24, 90, 91}) cases.push_back(ssd_case(1917, classes, S::Random));
  cases.push_back(ssd_case(1917, 23, S::Random, softmax));
  cases.push_back(ssd_case(1917, 23, S::Sparse));
  cases.push_back(ssd_case(1917, 23, S::Sparse, softmax));
  for (int anchors : {1, 7, 1000, 2053}) {
    cases.push_back(ssd_case(anchors, 2, S::Random));
    cases.push_back(ssd_case(anchors, 24, S::Random, softmax));
  }
  cases.push_back(ssd_case(1917, 23, S::Ties));
  cases.push_back(ssd_case(1917, 23, S::Ties, softmax));
  cases.push_back(ssd_case(1000, 3, S::Ties, sigmoid, 5, 7));
  cases.push_back(ssd_case(500, 24, S::IdenticalBoxes));
  cases.push_back(ssd_case(1000, 24, S::DisjointBoxes));
  cases.push_back(ssd_case(1000, 3, S::DisjointBoxes, sigmoid, 1024, 5000));
  cases.push_back(ssd_case(2053, 5, S::Random, sigmoid, 1024, 1000));
  cases.push_back(ssd_case(1917, 23, S::NothingAbove));
  cases.push_back(ssd_case(1917, 23, S::NothingAbove, softmax));
  cases.push_back(ssd_case(1917, 23, S::Extreme));
  cases.push_back(ssd_case(1917, 23, S::Extreme, softmax));
  return cases;
}

}  // namespace flexsight::testing_support
