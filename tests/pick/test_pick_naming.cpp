// pick's naming step (host/pick/pick_naming.h) with the shipped namer on the namer's
// fixture render: one naming per group of overlapping boxes, the group's best box posed
// as the namer's best classes, in the mix's order.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "host/detect/part_namer.h"
#include "host/io/input_error.h"
#include "host/pick/pick_naming.h"

namespace flexsight {
namespace {

const std::string kNamer = std::string(FLEXSIGHT_SOURCE_DIR) + "/models/tless-namer/model.onnx";
const std::string kFixture = std::string(FLEXSIGHT_TEST_DATA_DIR) + "/detect/namer";

ObjectDetection detection(int category_id, float score, float x0, float y0, float x1, float y1) {
  ObjectDetection d;
  d.category_id = category_id;
  d.score = score;
  d.box[0] = x0, d.box[1] = y0, d.box[2] = x1, d.box[3] = y1;
  return d;
}

struct Fixture {
  cv::Mat bgr;
  std::vector<std::vector<float>> boxes;  // xyxy of the fixture's parts
  std::vector<int> obj_ids;
};

Fixture fixture() {
  const nlohmann::json parts = nlohmann::json::parse(std::ifstream(kFixture + "/parts.json"));
  Fixture f;
  f.bgr = cv::imread(kFixture + "/" + parts["image"].get<std::string>(), cv::IMREAD_COLOR);
  for (const auto& part : parts["parts"]) {
    const std::vector<float> b = part["bbox"].get<std::vector<float>>();
    f.boxes.push_back({b[0], b[1], b[0] + b[2], b[1] + b[3]});
    f.obj_ids.push_back(part["obj_id"].get<int>());
  }
  return f;
}

TEST(PickNaming, EachGroupIsNamedOnceAtItsBestBox) {
  PartNamer namer(kNamer);
  const Fixture f = fixture();
  ASSERT_GE(f.boxes.size(), 2u);
  const std::vector<float>& a = f.boxes[0];
  const std::vector<float>& b = f.boxes[1];
  // Part a found twice (a shifted box of another class, IoU > 0.5 with the first), part b once.
  const std::vector<ObjectDetection> detections = {
      detection(7, 0.2f, b[0], b[1], b[2], b[3]), detection(5, 0.6f, a[0], a[1], a[2], a[3]),
      detection(9, 0.3f, a[0] + 2, a[1] + 2, a[2] + 2, a[3] + 2)};
  const int k = 3;
  const std::vector<NamedProposal> proposals = named_proposals(detections, namer, f.bgr, k, 0.5, NamingMix::Namer);
  ASSERT_EQ(proposals.size(), 2u * k);
  for (int group = 0; group < 2; ++group) {
    // Groups in the detector's order: part a's 0.6 box first.
    const ObjectDetection& lead = detections[group == 0 ? 1 : 0];
    const std::vector<float> p = namer.name(f.bgr, lead.box);
    const int best = static_cast<int>(std::max_element(p.begin(), p.end()) - p.begin());
    const NamedProposal& first = proposals[group * k];
    EXPECT_EQ(first.detection.category_id, namer.labels()[best].category_id);
    EXPECT_FLOAT_EQ(static_cast<float>(first.naming_score), p[best]);
    for (int i = 0; i < k; ++i) {
      const NamedProposal& named = proposals[group * k + i];
      EXPECT_TRUE(std::equal(named.detection.box, named.detection.box + 4, lead.box));
      if (i > 0) EXPECT_LE(named.naming_score, proposals[group * k + i - 1].naming_score);
    }
  }
  // The detector's score of a named class in its group rides along (0 when it did not propose it).
  for (int i = 0; i < 2 * k; ++i) {
    const int c = proposals[i].detection.category_id;
    const float expected = i < k ? (c == 5 ? 0.6f : c == 9 ? 0.3f : 0.0f) : (c == 7 ? 0.2f : 0.0f);
    EXPECT_FLOAT_EQ(proposals[i].detection.score, expected) << "proposal " << i;
  }
}

TEST(PickNaming, TheProductFavoursTheDetectorsClasses) {
  PartNamer namer(kNamer);
  const Fixture f = fixture();
  const std::vector<float>& a = f.boxes[0];
  const std::vector<float> p = namer.name(f.bgr, a.data());
  // The namer's least likely class, proposed by the detector with full confidence: times
  // (1 + 0.05) against at most (0 + 0.05) for the others, it comes first unless the namer
  // rules it out by more than 21 to 1.
  const int least = static_cast<int>(std::min_element(p.begin(), p.end()) - p.begin());
  const int category = namer.labels()[least].category_id;
  const std::vector<ObjectDetection> detections = {detection(category, 1.0f, a[0], a[1], a[2], a[3])};
  const std::vector<NamedProposal> product = named_proposals(detections, namer, f.bgr, 1, 0.5, NamingMix::Product);
  ASSERT_EQ(product.size(), 1u);
  const float top = *std::max_element(p.begin(), p.end());
  if (p[least] * 1.05f > top * 0.05f) {
    EXPECT_EQ(product[0].detection.category_id, category);
  } else {
    EXPECT_NE(product[0].detection.category_id, category);
  }
  EXPECT_EQ(parse_naming_mix("product", "option --namer-mix"), NamingMix::Product);
  EXPECT_THROW(parse_naming_mix("both", "option --namer-mix"), InputError);
}

}  // namespace
}  // namespace flexsight
