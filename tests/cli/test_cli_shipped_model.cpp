// The shipped detector (models/tless-ssd): its folder is complete and names the T-LESS
// parts of the CAD folder, it scores above a floor on held-out images it never saw
// (tests/data/detect/tless_synth_8: another seed, other backgrounds), and its
// post-processing gives the same bytes on the OpenCL and the reference path on real
// network outputs. Used by default, so these run the commands without --model.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>

#include "tests/cli/cli_test_support.h"

namespace {

namespace fs = std::filesystem;
using namespace flexsight::cli_test_support;
using Json = nlohmann::json;

const std::string kModelDir = std::string(FLEXSIGHT_SOURCE_DIR) + "/models/tless-ssd";
const std::string kHeldOut = std::string(FLEXSIGHT_TEST_DATA_DIR) + "/detect/tless_synth_8";

// mAP@0.5 (VOC) of the shipped model on the eight held-out images is 0.472 (its
// README); the floor leaves room for eight images' worth of chance but fails a model that
// lost its training or a pipeline that broke boxes or classes.
constexpr double kMap50Floor = 0.28;

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(ShippedModel, FolderIsCompleteAndNamesTheTlessParts) {
  for (const char* name : {"model.onnx", "anchors.csv", "labels.txt", "model.json", "README.md"}) {
    ASSERT_TRUE(fs::exists(kModelDir + "/" + name)) << name;
  }
  EXPECT_LE(fs::file_size(kModelDir + "/model.onnx"), 25u * 1024 * 1024);
  const Json settings = Json::parse(read_file(kModelDir + "/model.json"));
  EXPECT_EQ(settings["score_function"], "softmax");
  EXPECT_EQ(settings["input_size"], 300);
  // labels.txt: background, then one line per STL of the CAD folder, ids from the names.
  std::set<int> cad_ids;
  for (const auto& entry : fs::directory_iterator(std::string(FLEXSIGHT_TLESS_CAD_DIR))) {
    const std::string stem = entry.path().stem().string();  // obj_05
    cad_ids.insert(std::stoi(stem.substr(stem.find('_') + 1)));
  }
  ASSERT_EQ(cad_ids.size(), 23u);
  std::istringstream labels(read_file(kModelDir + "/labels.txt"));
  std::set<int> label_ids;
  int index = 0, category = 0;
  std::string label;
  while (labels >> index >> category >> label) {
    if (index > 0) label_ids.insert(category);
  }
  EXPECT_EQ(label_ids, cad_ids);
}

TEST(ShippedModel, ScoresAboveItsFloorOnHeldOutImages) {
  const fs::path dir = fresh_temp_dir("ShippedModelScores");
  const RunResult r = run_flexsight("eval-det " + kHeldOut + " --out " + (dir / "eval").string() +
                                        " --quiet --device reference",
                                    dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Json report = Json::parse(read_file((dir / "eval" / "report.json").string()));
  EXPECT_GE(report["map50"].get<double>(), kMap50Floor) << r.out;
  EXPECT_GT(report["map50_95"].get<double>(), 0.0);
  EXPECT_LE(report["map50_95"].get<double>(), report["map50"].get<double>());
  fs::remove_all(dir);
}

TEST(ShippedModel, OpenClAndReferencePostProcessingGiveTheSameBytes) {
  const fs::path dir = fresh_temp_dir("ShippedModelPaths");
  const std::string images = kHeldOut + "/000000/rgb";
  const std::string reference = (dir / "reference.json").string();
  const std::string opencl = (dir / "opencl.json").string();
  // A low threshold: many candidates per class, so that NMS has work to do.
  RunResult r = run_flexsight("detect " + images + " -o " + reference +
                                  " --score 0.05 --quiet --device reference",
                              dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_flexsight("detect " + images + " -o " + opencl + " --score 0.05 --quiet --device opencl", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string bytes = read_file(reference);
  EXPECT_GT(Json::parse(bytes).size(), 8u);
  EXPECT_EQ(bytes, read_file(opencl));
  fs::remove_all(dir);
}

}  // namespace
