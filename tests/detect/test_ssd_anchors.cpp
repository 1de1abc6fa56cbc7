// The anchor generator against values derived by hand from the TF OD API's formulas
// (create_ssd_anchors, tile_anchors), and the anchors file reader's errors.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "host/detect/ssd_anchors.h"
#include "host/io/input_error.h"
#include "tests/common/test_support.h"

namespace flexsight {
namespace {

struct Anchor {
  float ycenter, xcenter, height, width;
};

Anchor anchor_at(const std::vector<float>& anchors, int index) {
  return {anchors[4 * index], anchors[4 * index + 1], anchors[4 * index + 2],
          anchors[4 * index + 3]};
}

void expect_anchor(const std::vector<float>& anchors, int index, double ycenter, double xcenter,
                   double height, double width) {
  const Anchor a = anchor_at(anchors, index);
  EXPECT_NEAR(a.ycenter, ycenter, 1e-6) << "anchor " << index;
  EXPECT_NEAR(a.xcenter, xcenter, 1e-6) << "anchor " << index;
  EXPECT_NEAR(a.height, height, 1e-6) << "anchor " << index;
  EXPECT_NEAR(a.width, width, 1e-6) << "anchor " << index;
}

TEST(SsdAnchors, MobileNetV2SetHas1917Anchors) {
  const std::vector<float> anchors = generate_ssd_anchors();
  ASSERT_EQ(anchors.size(), 4u * kSsdMobileNetV2AnchorCount);
  EXPECT_EQ(kSsdMobileNetV2AnchorCount, 19 * 19 * 3 + (10 * 10 + 5 * 5 + 3 * 3 + 2 * 2 + 1) * 6);
}

TEST(SsdAnchors, LowestLayerHasTheThreeReducedBoxes) {
  const std::vector<float> a = generate_ssd_anchors();
  // 19x19 grid: stride 1/19, first centre half a stride in. Specs (0.1, 1), (0.2, 2),
  // (0.2, 0.5): height = scale / sqrt(ratio), width = scale * sqrt(ratio).
  const double c0 = 0.5 / 19;
  expect_anchor(a, 0, c0, c0, 0.1, 0.1);
  expect_anchor(a, 1, c0, c0, 0.2 / std::sqrt(2.0), 0.2 * std::sqrt(2.0));
  expect_anchor(a, 2, c0, c0, 0.2 / std::sqrt(0.5), 0.2 * std::sqrt(0.5));
  // Next column, then next row (row-major cells, specs innermost).
  expect_anchor(a, 3, c0, 1.5 / 19, 0.1, 0.1);
  expect_anchor(a, 3 * 19, 1.5 / 19, c0, 0.1, 0.1);
  expect_anchor(a, 1082, 18.5 / 19, 18.5 / 19, 0.2 / std::sqrt(0.5), 0.2 * std::sqrt(0.5));
}

TEST(SsdAnchors, UpperLayersHaveFiveRatiosAndTheInterpolatedScale) {
  const std::vector<float> a = generate_ssd_anchors();
  // Layer 1 (10x10) starts at 1083 with scale 0.2 + 0.75 / 5 = 0.35; its sixth box has
  // scale sqrt(0.35 * 0.5) and ratio 1.
  const double s1 = 0.35;
  expect_anchor(a, 1083, 0.05, 0.05, s1, s1);
  expect_anchor(a, 1084, 0.05, 0.05, s1 / std::sqrt(2.0), s1 * std::sqrt(2.0));
  expect_anchor(a, 1085, 0.05, 0.05, s1 / std::sqrt(0.5), s1 * std::sqrt(0.5));
  expect_anchor(a, 1086, 0.05, 0.05, s1 / std::sqrt(3.0), s1 * std::sqrt(3.0));
  expect_anchor(a, 1087, 0.05, 0.05, s1 / std::sqrt(0.3333), s1 * std::sqrt(0.3333));
  expect_anchor(a, 1088, 0.05, 0.05, std::sqrt(0.35 * 0.5), std::sqrt(0.35 * 0.5));
  expect_anchor(a, 1089, 0.05, 0.15, s1, s1);
  // Layer 2 (5x5) at 1683, scale 0.5; layer 3 (3x3) at 1833, 0.65; layer 4 (2x2) at
  // 1887, 0.8; layer 5 (1x1) at 1911, 0.95, interpolated with 1.0.
  expect_anchor(a, 1683, 0.1, 0.1, 0.5, 0.5);
  expect_anchor(a, 1833, 1.0 / 6, 1.0 / 6, 0.65, 0.65);
  expect_anchor(a, 1887, 0.25, 0.25, 0.8, 0.8);
  expect_anchor(a, 1911, 0.5, 0.5, 0.95, 0.95);
  expect_anchor(a, 1916, 0.5, 0.5, std::sqrt(0.95), std::sqrt(0.95));
}

TEST(SsdAnchors, ConfigWithoutTheReducedLowestLayer) {
  SsdAnchorConfig config;
  config.feature_maps = {2, 1};
  config.reduce_boxes_in_lowest_layer = false;
  config.aspect_ratios = {1.0f, 4.0f};
  const std::vector<float> a = generate_ssd_anchors(config);
  // (2*2 + 1) cells x (2 ratios + interpolated) boxes; scales 0.2 and 0.95.
  ASSERT_EQ(a.size(), 4u * 15);
  expect_anchor(a, 0, 0.25, 0.25, 0.2, 0.2);
  expect_anchor(a, 1, 0.25, 0.25, 0.1, 0.4);
  expect_anchor(a, 2, 0.25, 0.25, std::sqrt(0.2 * 0.95), std::sqrt(0.2 * 0.95));
  expect_anchor(a, 14, 0.5, 0.5, std::sqrt(0.95), std::sqrt(0.95));
}

class SsdAnchorFile : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = testing_support::fresh_temp_dir("ssd_anchor_file"); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(path(name), std::ios::binary) << text;
    return path(name);
  }
  // The InputError message of reading `file`, which must throw one.
  static std::string error_of(const std::string& file, int expected_count) {
    try {
      read_anchor_file(file, expected_count);
    } catch (const InputError& error) {
      return error.what();
    }
    ADD_FAILURE() << "no InputError for " << file;
    return {};
  }
  std::filesystem::path dir_;
};

TEST_F(SsdAnchorFile, RoundTripKeepsEveryFloat) {
  const std::vector<float> anchors = generate_ssd_anchors();
  write_anchor_file(path("anchors.csv"), anchors);
  EXPECT_EQ(read_anchor_file(path("anchors.csv"), kSsdMobileNetV2AnchorCount), anchors);
  EXPECT_EQ(read_anchor_file(path("anchors.csv"), 0), anchors) << "0: any count";
}

TEST_F(SsdAnchorFile, ReadsWhatNumPyWrites) {
  // np.savetxt(..., fmt="%.9g", delimiter=",", header=..., comments=""), CRLF too.
  const std::string file = write("numpy.csv",
                                 "ycenter,xcenter,height,width\r\n"
                                 "0.0263157897,0.0263157897,0.100000001,0.100000001\r\n"
                                 "5e-01,0.5,1,0.974679434\r\n");
  const std::vector<float> expected = {0.0263157897f, 0.0263157897f, 0.100000001f, 0.100000001f,
                                       0.5f, 0.5f, 1.0f, 0.974679434f};
  EXPECT_EQ(read_anchor_file(file, 2), expected);
}

TEST_F(SsdAnchorFile, MissingFileNamesIt) {
  const std::string missing = path("absent.csv");
  const std::string message = error_of(missing, 0);
  EXPECT_NE(message.find(missing), std::string::npos) << message;
  EXPECT_NE(message.find("does not exist"), std::string::npos) << message;
}

TEST_F(SsdAnchorFile, WrongCountNamesBothCounts) {
  std::vector<float> anchors = generate_ssd_anchors();
  anchors.resize(anchors.size() - 4);
  write_anchor_file(path("short.csv"), anchors);
  const std::string message = error_of(path("short.csv"), kSsdMobileNetV2AnchorCount);
  EXPECT_NE(message.find(path("short.csv")), std::string::npos) << message;
  EXPECT_NE(message.find("holds 1916 anchors, the model outputs 1917"), std::string::npos)
      << message;
}

TEST_F(SsdAnchorFile, MalformedContentNamesFileAndLine) {
  const std::string header = "ycenter,xcenter,height,width\n";
  const std::string good = "0.5,0.5,0.1,0.1\n";
  struct Bad {
    const char* name;
    std::string text;
    const char* expected;
  };
  const Bad bad[] = {
      {"empty.csv", "", "is empty"},
      {"header.csv", "xcenter,ycenter,width,height\n" + good, "first line must be"},
      {"only_header.csv", header, "holds no anchors"},
      {"three.csv", header + good + "0.5,0.5,0.1\n", "line 3: expected 4 comma-separated"},
      {"five.csv", header + "0.5,0.5,0.1,0.1,0.2\n", "line 2: expected 4 comma-separated"},
      {"word.csv", header + "0.5,abc,0.1,0.1\n", "line 2: expected 4 comma-separated"},
      {"spaces.csv", header + "0.5 0.5 0.1 0.1\n", "line 2: expected 4 comma-separated"},
      {"nan.csv", header + "nan,0.5,0.1,0.1\n", "line 2: values must be finite"},
      {"zero.csv", header + good + good + "0.5,0.5,0,0.1\n", "line 4: height and width must be positive"},
      {"negative.csv", header + "0.5,0.5,0.1,-0.1\n", "line 2: height and width must be positive"},
  };
  for (const Bad& b : bad) {
    const std::string file = write(b.name, b.text);
    const std::string message = error_of(file, 0);
    EXPECT_EQ(message.rfind(file + ": ", 0), 0u) << message;
    EXPECT_NE(message.find(b.expected), std::string::npos) << b.name << ": " << message;
  }
}

// The training script's anchors (scripts/detect/anchors.py, run as detect.anchors; what the
// exported model's sidecar holds) are the C++ generator's: the same layout, order and sizes. Not the same
// floats: the C++ generator repeats TF's float32 arithmetic (centres as row * stride +
// offset in float), NumPy computes in doubles and rounds once, so about a quarter of the
// values differ in their last bits (5e-5 relative at most). Inference decodes against
// the sidecar shipped with the model, so the trained anchors are the ones used.
TEST_F(SsdAnchorFile, TrainingScriptWritesTheSameAnchors) {
  const std::string file = path("python_anchors.csv");
  const std::string command = "PYTHONPATH=" + std::string(FLEXSIGHT_SOURCE_DIR) + "/scripts " +
                              FLEXSIGHT_PYTHON_BIN + " -m detect.anchors " + file;
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  const std::vector<float> trained = read_anchor_file(file, kSsdMobileNetV2AnchorCount);
  const std::vector<float> generated = generate_ssd_anchors();
  ASSERT_EQ(trained.size(), generated.size());
  for (size_t i = 0; i < trained.size(); ++i) {
    EXPECT_NEAR(trained[i], generated[i], 1e-4 * std::fabs(generated[i])) << "value " << i;
  }
}

}  // namespace
}  // namespace flexsight
