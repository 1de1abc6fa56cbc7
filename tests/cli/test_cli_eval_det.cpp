// `flexsight eval-det` end to end: the reports and pictures of a small COCO data set and
// a BOP scene with detections whose APs are worked out by hand, and bad input: a clear
// error naming the file or option, exit code 1, and the work folder exactly as it was.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "tests/cli/cli_test_support.h"
#include "tests/common/test_support.h"
#include "tests/detect/detector_fixture.h"

using flexsight::testing_support::read_text;
using flexsight::testing_support::tiny_ssd_dir;
using flexsight::testing_support::tiny_ssd_image;
using flexsight::testing_support::tiny_ssd_model;

using namespace flexsight::cli_test_support;
using Json = nlohmann::json;

namespace {

constexpr int kWidth = 64, kHeight = 48;

void write_json(const fs::path& path, const Json& json) { std::ofstream(path) << json.dump(); }

Json read_json(const fs::path& path) {
  std::ifstream in(path);
  return Json::parse(in);
}

// Three images (COCO ids 7, 3, 11, listed out of order) of classes 1 "one" and 2 "two":
//   image 3: class 1 at [4, 4, 20, 16]; image 7: class 2 at [30, 10, 20, 20];
//   image 11: class 1 at [10, 20, 30, 20].
// The detections find all three exactly, but the best-scored one is a class-1 box on
// image 7 where there is none. Class 1: false positive, hit, hit: VOC points (0, 0),
// (1/2, 1/2), (1, 2/3), envelope 2/3 everywhere, AP 2/3; the same for COCO at every IoU
// threshold (exact boxes) and all 101 recall points. Class 2: AP 1. Means: 5/6.
class EvalDetCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = flexsight::testing_support::fresh_temp_dir(
        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    work_ = dir_ / "work";
    logs_ = dir_ / "logs";
    data_ = work_ / "data";
    out_ = work_ / "out";
    fs::create_directories(data_ / "rgb");
    fs::create_directories(logs_);
    Json images = Json::array(), annotations = Json::array();
    const int ids[] = {7, 3, 11};
    const Json boxes[] = {{30, 10, 20, 20}, {4, 4, 20, 16}, {10, 20, 30, 20}};
    const int classes[] = {2, 1, 1};
    for (int i = 0; i < 3; ++i) {
      const std::string file = "rgb/" + std::to_string(ids[i]) + ".png";
      cv::imwrite((data_ / file).string(), flexsight::testing_support::random_rgb8(kWidth, kHeight, i + 1));
      images.push_back({{"id", ids[i]}, {"file_name", file}, {"width", kWidth}, {"height", kHeight},
                        {"scene_id", 0}, {"im_id", ids[i]}});
      annotations.push_back({{"id", i + 1}, {"image_id", ids[i]}, {"category_id", classes[i]},
                             {"bbox", boxes[i]}, {"area", 100.0},
                             {"segmentation", {{"size", {kHeight, kWidth}}, {"counts", {kWidth * kHeight}}}},
                             {"iscrowd", 0}});
    }
    coco_ = {{"images", images},
             {"annotations", annotations},
             {"categories", {{{"id", 1}, {"name", "one"}}, {{"id", 2}, {"name", "two"}}}}};
    write_json(data_ / "coco_instances.json", coco_);
    detections_ = {
        {{"image_id", 3}, {"category_id", 1}, {"bbox", {4, 4, 20, 16}}, {"score", 0.9}},
        {{"image_id", 11}, {"category_id", 1}, {"bbox", {10, 20, 30, 20}}, {"score", 0.8}},
        {{"image_id", 7}, {"category_id", 1}, {"bbox", {40, 30, 10, 10}}, {"score", 0.95}},
        {{"image_id", 7}, {"category_id", 2}, {"bbox", {30, 10, 20, 20}}, {"score", 0.6}},
    };
    write_json(results(), detections_);
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir_);
  }

  std::string results() const { return (work_ / "dets.json").string(); }
  std::string command(const std::string& results_path) const {
    return "eval-det " + data_.string() + " --results " + results_path + " --out " + out_.string();
  }
  RunResult run(const std::string& arguments) { return run_flexsight(arguments, logs_); }

  // `arguments` must fail, naming `must_mention`, and leave the work folder as it was.
  void expect_rejected(const std::string& arguments, const std::string& must_mention) {
    const auto before = snapshot(work_);
    const RunResult r = run(arguments);
    EXPECT_EQ(r.exit_code, 1) << arguments << "\n" << r.err;
    EXPECT_NE(r.err.find("error"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(must_mention), std::string::npos) << arguments << "\n" << r.err;
    EXPECT_EQ(snapshot(work_), before) << arguments;
  }
  // The detections file with entry `index`'s `key` set to `value` (raw JSON text).
  std::string results_with(std::size_t index, const std::string& key, const std::string& value) {
    Json edited = detections_;
    edited[index][key] = "@@";
    std::string text = edited.dump();
    text.replace(text.find("\"@@\""), 4, value);
    const fs::path path = work_ / ("dets_" + key + ".json");
    std::ofstream(path) << text;
    return path.string();
  }

  fs::path dir_, work_, logs_, data_, out_;
  Json coco_, detections_;
};

TEST_F(EvalDetCli, WritesReportsAndPictures) {
  const RunResult r = run(command(results()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("mAP@0.5 0.8333"), std::string::npos) << r.out;
  const Json report = read_json(out_ / "report.json");
  for (const char* key : {"map50", "map50_95", "ap50_coco", "ap75", "map_at_iou_threshold"}) {
    ASSERT_TRUE(report.contains(key)) << key;
    EXPECT_GE(report[key].get<double>(), 0.0) << key;
    EXPECT_LE(report[key].get<double>(), 1.0) << key;
  }
  EXPECT_NEAR(report["map50"].get<double>(), 5.0 / 6.0, 1e-12);
  EXPECT_NEAR(report["map50_95"].get<double>(), 5.0 / 6.0, 1e-12);
  EXPECT_NEAR(report["ap50_coco"].get<double>(), 5.0 / 6.0, 1e-12);
  EXPECT_NEAR(report["ap75"].get<double>(), 5.0 / 6.0, 1e-12);
  EXPECT_EQ(report["images"], 3);
  EXPECT_EQ(report["detections"], 4);
  EXPECT_EQ(report["ground_truth_boxes"], 3);
  EXPECT_EQ(report["detections_file"], results());
  EXPECT_EQ(report["detections_format"], "COCO results");
  ASSERT_EQ(report["classes"].size(), 2u);
  const Json& one = report["classes"][0];
  EXPECT_EQ(one["category_id"], 1);
  EXPECT_EQ(one["name"], "one");
  EXPECT_EQ(one["ground_truth"], 2);
  EXPECT_EQ(one["detections"], 3);
  EXPECT_NEAR(one["voc_ap50"].get<double>(), 2.0 / 3.0, 1e-12);
  EXPECT_NEAR(one["coco_ap"].get<double>(), 2.0 / 3.0, 1e-12);
  EXPECT_EQ(report["classes"][1]["voc_ap50"], 1.0);

  // Class-agnostic: 0.95 (a false positive), then three hits: points (1/3, 0),
  // (1/3, 1/2), (2/3, 2/3), (1, 3/4), envelope 3/4 everywhere -> AP 0.75, and the same
  // at every COCO threshold (exact boxes). Every part is below 32 px (sqrt of its area:
  // 17.9, 20, 24.5); so is the false positive (10 px), so the <32 bin keeps it.
  const Json& agnostic = report["class_agnostic"];
  EXPECT_NEAR(agnostic["ap50"].get<double>(), 0.75, 1e-12);
  EXPECT_NEAR(agnostic["coco_ap"].get<double>(), 0.75, 1e-12);
  EXPECT_EQ(agnostic["recall_score"], 0.3);
  EXPECT_EQ(agnostic["recall_at_score"], 1.0);
  EXPECT_NEAR(agnostic["per_class"]["ap50"].get<double>(), 5.0 / 6.0, 1e-12);
  ASSERT_EQ(report["by_size"].size(), 4u);
  const Json& small = report["by_size"][0];
  EXPECT_EQ(small["label"], "<32");
  EXPECT_EQ(small["class_agnostic"]["ground_truth"], 3);
  EXPECT_NEAR(small["class_agnostic"]["ap50"].get<double>(), 0.75, 1e-12);
  EXPECT_NEAR(small["per_class"]["ap50"].get<double>(), 5.0 / 6.0, 1e-12);
  EXPECT_EQ(report["by_size"][1]["class_agnostic"]["ground_truth"], 0);
  EXPECT_TRUE(report["by_size"][1]["class_agnostic"]["ap50"].is_null());
  EXPECT_TRUE(report["by_size"][3]["size_px"][1].is_null());  // no upper bound
  EXPECT_NE(r.out.find("class-agnostic AP@0.5 0.7500, AP@[.5:.95] 0.7500"), std::string::npos) << r.out;

  const std::string markdown = slurp(out_ / "report.md");
  EXPECT_NE(markdown.find("| mAP@0.5 (VOC all-point) | 0.8333 |"), std::string::npos) << markdown;
  EXPECT_NE(markdown.find("| all | 3 | 0.8333 | 1.0000 | 1.0000 | 0.7500 | 1.0000 | 1.0000 |"), std::string::npos)
      << markdown;
  EXPECT_NE(markdown.find("| 1 | one | 2 | 3 | 0.6667 |"), std::string::npos) << markdown;
  const cv::Mat curves = cv::imread((out_ / "pr_curve.png").string());
  EXPECT_GE(curves.cols, 800);
  EXPECT_GE(curves.rows, 600);
  const cv::Mat montage = cv::imread((out_ / "montage.jpg").string());
  EXPECT_FALSE(montage.empty());
  // Only the outputs, no staging folder beside them.
  EXPECT_EQ(snapshot(work_).count("out/report.md"), 1u);
  for (const auto& entry : fs::directory_iterator(work_)) {
    EXPECT_EQ(entry.path().filename().string().find(".staging"), std::string::npos) << entry.path();
  }
}

TEST_F(EvalDetCli, BopFormOfTheSameDetectionsScoresTheSame) {
  Json bop = Json::array();
  for (const Json& d : detections_) {
    bop.push_back({{"scene_id", 0}, {"image_id", d["image_id"]}, {"category_id", d["category_id"]},
                   {"bbox", d["bbox"]}, {"score", d["score"]}, {"time", 0.02}});
  }
  write_json(work_ / "bop.json", bop);
  const RunResult r = run(command((work_ / "bop.json").string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Json report = read_json(out_ / "report.json");
  EXPECT_EQ(report["detections_format"], "BOP results");
  EXPECT_NEAR(report["map50"].get<double>(), 5.0 / 6.0, 1e-12);
  EXPECT_NEAR(report["map50_95"].get<double>(), 5.0 / 6.0, 1e-12);
}

TEST_F(EvalDetCli, RecallScoreSetsTheOperatingPoint) {
  // The hits score 0.9, 0.8 and 0.6: from 0.7, two of three.
  const RunResult r = run(command(results()) + " --recall-score 0.7 --montage 0");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Json report = read_json(out_ / "report.json");
  EXPECT_NEAR(report["class_agnostic"]["recall_at_score"].get<double>(), 2.0 / 3.0, 1e-12);
  EXPECT_EQ(report["class_agnostic"]["recall_any"], 1.0);
  EXPECT_NE(r.out.find("rec>=0.7"), std::string::npos) << r.out;
}

TEST_F(EvalDetCli, MontageHoldsTheFirstImages) {
  ASSERT_EQ(run(command(results()) + " --montage 2").exit_code, 0);
  const cv::Mat two = cv::imread((out_ / "montage.jpg").string());
  ASSERT_EQ(run(command(results()) + " --montage 3 --overwrite").exit_code, 0);
  const cv::Mat three = cv::imread((out_ / "montage.jpg").string());
  EXPECT_LT(two.cols, three.cols);  // one row of a 4-column grid: 2 tiles, then 3
  ASSERT_EQ(run(command(results()) + " --montage 0 --overwrite").exit_code, 0);
  EXPECT_FALSE(fs::exists(out_ / "montage.jpg"));
  EXPECT_TRUE(fs::exists(out_ / "pr_curve.png"));
}

TEST_F(EvalDetCli, IouThresholdMovesTheVocMetricOnly) {
  // Class 2's detection moved right by 4 px: IoU 16 x 20 / (800 - 320) = 2/3. A hit at
  // 0.5, a miss at 0.7; map50 stays at 0.5.
  detections_[3]["bbox"] = {34, 10, 20, 20};
  write_json(results(), detections_);
  ASSERT_EQ(run(command(results()) + " --iou-threshold 0.7").exit_code, 0);
  const Json report = read_json(out_ / "report.json");
  EXPECT_EQ(report["iou_threshold"], 0.7);
  EXPECT_NEAR(report["map50"].get<double>(), 5.0 / 6.0, 1e-12);
  EXPECT_NEAR(report["map_at_iou_threshold"].get<double>(), (2.0 / 3.0 + 0.0) / 2, 1e-12);
  EXPECT_EQ(report["classes"][1]["voc_ap_at_iou_threshold"], 0.0);
  EXPECT_NE(slurp(out_ / "report.md").find("VOC AP@0.7"), std::string::npos);
}

TEST_F(EvalDetCli, ScoresABopFolder) {
  // tests/data/bop_tless_like: image 0 holds objects 2 at [3, 4, 9, 7] and 25 at
  // [9, 7, 13, 11], image 1 object 5 at [20, 10, 7, 5] (bbox_visib).
  const fs::path bop = work_ / "bop";
  fs::copy(std::string(FLEXSIGHT_TEST_DATA_DIR) + "/bop_tless_like", bop, fs::copy_options::recursive);
  const Json found = {
      {{"scene_id", 1}, {"image_id", 0}, {"category_id", 2}, {"bbox", {3, 4, 9, 7}}, {"score", 0.9}},
      {{"scene_id", 1}, {"image_id", 0}, {"category_id", 25}, {"bbox", {9, 7, 13, 11}}, {"score", 0.8}},
      {{"scene_id", 1}, {"image_id", 1}, {"category_id", 5}, {"bbox", {20, 10, 7, 5}}, {"score", 0.7}},
  };
  write_json(work_ / "bop_dets.json", found);
  const std::string arguments =
      "eval-det " + bop.string() + " --results " + (work_ / "bop_dets.json").string() + " --out " + out_.string();
  RunResult r = run(arguments);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  Json report = read_json(out_ / "report.json");
  EXPECT_EQ(report["dataset_format"], "BOP");
  EXPECT_EQ(report["map50"], 1.0);
  EXPECT_NEAR(report["map50_95"].get<double>(), 1.0, 1e-12);  // COCO's precision: 1 / (1 + 2^-52)
  EXPECT_EQ(report["classes_with_ground_truth"], 3);
  EXPECT_FALSE(cv::imread((out_ / "montage.jpg").string()).empty());

  // A fourth object (7) hidden behind the others (visib_fract 0, no box) is no ground
  // truth: the scores stay, and class 7 has none.
  Json gt = read_json(bop / "000001" / "scene_gt.json");
  Json info = read_json(bop / "000001" / "scene_gt_info.json");
  gt["1"].push_back(gt["1"][0]);
  gt["1"][1]["obj_id"] = 7;
  info["1"].push_back({{"bbox_obj", {1, 1, 5, 5}}, {"bbox_visib", {-1, -1, -1, -1}}, {"px_count_all", 25},
                       {"px_count_valid", 25}, {"px_count_visib", 0}, {"visib_fract", 0.0}});
  write_json(bop / "000001" / "scene_gt.json", gt);
  write_json(bop / "000001" / "scene_gt_info.json", info);
  r = run(arguments + " --overwrite --montage 0");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  report = read_json(out_ / "report.json");
  EXPECT_EQ(report["map50"], 1.0);
  EXPECT_EQ(report["ground_truth_boxes"], 3);
  ASSERT_EQ(report["classes"].size(), 4u);  // 2, 5, 7, 25
  const Json& hidden = report["classes"][2];
  EXPECT_EQ(hidden["category_id"], 7);
  EXPECT_EQ(hidden["ground_truth"], 0);
  EXPECT_TRUE(hidden["voc_ap50"].is_null());
  EXPECT_TRUE(hidden["coco_ap"].is_null());

  // From --min-visible 0.95 the parts less visible are crowd regions, no targets.
  int at_least_095 = 0;
  for (const auto& [image, parts] : info.items()) {
    for (const Json& part : parts) at_least_095 += part["visib_fract"].get<double>() >= 0.95 ? 1 : 0;
  }
  ASSERT_LT(at_least_095, 3);
  r = run(arguments + " --overwrite --montage 0 --min-visible 0.95");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  report = read_json(out_ / "report.json");
  EXPECT_EQ(report["ground_truth_boxes"], at_least_095);
  EXPECT_EQ(report["crowd_regions"], 3 - at_least_095);

  // COCO results name COCO image ids, which a BOP folder has not.
  expect_rejected("eval-det " + bop.string() + " --results " + results() + " --out " + (work_ / "o2").string(),
                  "BOP folder");
}

TEST_F(EvalDetCli, RejectsMissingInputsAndBadOptions) {
  const std::string nope = (work_ / "nope").string();
  expect_rejected("eval-det " + nope + " --results " + results() + " --out " + out_.string(), nope);
  expect_rejected("eval-det --results " + results() + " --out " + out_.string(), "DATASET");
  const std::string no_model = (work_ / "no_model.onnx").string();
  expect_rejected("eval-det " + data_.string() + " --model " + no_model + " --out " + out_.string(),
                  no_model);
  expect_rejected("eval-det " + data_.string() + " --results " + results(), "--out");
  const std::string missing = (work_ / "missing.json").string();
  expect_rejected(command(missing), missing);
  for (const char* value : {"0", "1.5", "half"}) {
    expect_rejected(command(results()) + " --iou-threshold " + value, "--iou-threshold");
  }
  expect_rejected(command(results()) + " --montage -1", "--montage");
  expect_rejected(command(results()) + " --montage many", "--montage");
  expect_rejected(command(results()) + " --model ssd.onnx", "--model");  // both sources
  for (const char* value : {"-0.1", "1.5", "nan"}) {
    expect_rejected("eval-det " + data_.string() + " --model " + tiny_ssd_model() + " --score " + value +
                        " --out " + out_.string(),
                    "--score");
  }
  // The tiny model's categories (5, 7, 9) are not this data set's (1, 2).
  expect_rejected("eval-det " + data_.string() + " --model " + tiny_ssd_model() + " --out " + out_.string(),
                  "other parts");
  expect_rejected(command(results()) + " --colour red", "--colour");
  const std::string no_parent = (work_ / "a" / "b").string();
  expect_rejected("eval-det " + data_.string() + " --results " + results() + " --out " + no_parent, no_parent);
  EXPECT_EQ(run("eval-det --help").exit_code, 0);
  EXPECT_EQ(run("eval-det").exit_code, 1);
}

TEST_F(EvalDetCli, RejectsBadDetectionFiles) {
  const fs::path garbled = work_ / "garbled.json";
  std::ofstream(garbled) << "[{\"image_id\": 3, ";
  expect_rejected(command(garbled.string()), garbled.string() + ": is not valid JSON");
  const fs::path object = work_ / "object.json";
  std::ofstream(object) << "{\"detections\": []}";
  expect_rejected(command(object.string()), "must be a JSON list");

  const std::string file = results();
  expect_rejected(command(results_with(0, "image_id", "999")), "entry 0: image_id 999 is not an image");
  // Python's json.dump writes float("nan") as a bare NaN.
  expect_rejected(command(results_with(1, "score", "NaN")), "entry 1: score is NaN");
  // A number beyond a double (found by tests/fuzz/fuzz_detection_results's sibling
  // fuzz_bop_json: nlohmann-json's out_of_range escaped the reader).
  expect_rejected(command(results_with(1, "score", "1e999")), "is not valid JSON (number overflow");
  expect_rejected(command(results_with(2, "score", "1.5")), "entry 2: score 1.5 is outside [0, 1]");
  expect_rejected(command(results_with(3, "score", "\"high\"")), "entry 3: score");
  expect_rejected(command(results_with(1, "bbox", "[4, 4, -20, 16]")), "entry 1: bbox [4,4,-20,16] has a negative");
  expect_rejected(command(results_with(1, "bbox", "[4, 4, 20]")), "entry 1: bbox");
  expect_rejected(command(results_with(0, "bbox", "[4, Infinity, 20, 16]")), "entry 0: bbox[1] is Infinity");
  expect_rejected(command(results_with(3, "category_id", "4")), "entry 3: category_id 4 is not a category");
  expect_rejected(command(results_with(2, "scene_id", "0")), "entry 2: has a scene_id");

  Json bop = {{{"scene_id", 0}, {"image_id", 42}, {"category_id", 1}, {"bbox", {1, 1, 2, 2}}, {"score", 0.5}}};
  write_json(work_ / "bop.json", bop);
  expect_rejected(command((work_ / "bop.json").string()), "scene_id 0, image_id (im_id) 42 is not an image");
}

TEST_F(EvalDetCli, RejectsBadDataSets) {
  // The montage reads the first images (in id order: 3 first).
  fs::rename(data_ / "rgb" / "3.png", work_ / "moved.png");
  expect_rejected(command(results()), (data_ / "rgb" / "3.png").string());
  fs::rename(work_ / "moved.png", data_ / "rgb" / "3.png");

  Json empty = coco_;
  empty["annotations"] = Json::array();
  write_json(data_ / "coco_instances.json", empty);
  expect_rejected(command(results()), "has no ground-truth box");
}

TEST_F(EvalDetCli, NonEmptyOutputFolderNeedsOverwrite) {
  fs::create_directories(out_);
  std::ofstream(out_ / "keep.txt") << "earlier work";
  expect_rejected(command(results()), out_.string() + ": exists and is not empty; pass --overwrite");
  const RunResult r = run(command(results()) + " --overwrite");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(fs::exists(out_ / "keep.txt"));
  EXPECT_TRUE(fs::exists(out_ / "report.json"));
}

}  // namespace

// --model runs the detector on every image. The data set is the tiny model's own picture
// with, as ground truth, NumPy's detections of it (expected_detections.json, made apart
// from the C++ code): the detector must find each of those boxes again, so that every
// class with ground truth scores AP 1 under both metrics.
TEST(EvalDetModel, RunsTheDetectorOnEveryImage) {
  const fs::path dir = flexsight::testing_support::fresh_temp_dir("EvalDetModel");
  const fs::path data = dir / "data";
  fs::create_directories(data / "rgb");
  fs::copy_file(tiny_ssd_image(), data / "rgb" / "000001.png");
  const Json expected = Json::parse(read_text(tiny_ssd_dir() + "/expected_detections.json"));
  const int categories[] = {5, 7, 9};
  const int width = 317, height = 241;
  Json annotations = Json::array();
  for (const Json& d : expected["detections"]) {
    const double x0 = d["box"][0].get<double>() * width, y0 = d["box"][1].get<double>() * height;
    const double x1 = d["box"][2].get<double>() * width, y1 = d["box"][3].get<double>() * height;
    annotations.push_back({{"id", annotations.size() + 1}, {"image_id", 1},
                           {"category_id", categories[d["class_id"].get<int>()]},
                           {"bbox", {x0, y0, x1 - x0, y1 - y0}}, {"area", (x1 - x0) * (y1 - y0)},
                           {"segmentation", {{"size", {height, width}}, {"counts", {width * height}}}},
                           {"iscrowd", 0}});
  }
  const Json coco = {
      {"images", {{{"id", 1}, {"file_name", "rgb/000001.png"}, {"width", width}, {"height", height}}}},
      {"annotations", annotations},
      {"categories", {{{"id", 5}, {"name", "red_box"}}, {{"id", 7}, {"name", "green_box"}},
                      {{"id", 9}, {"name", "blue_box"}}}}};
  write_json(data / "coco_instances.json", coco);
  const fs::path out = dir / "out";
  const RunResult r = run_flexsight("eval-det " + data.string() + " --model " + tiny_ssd_model() +
                                        " --score " + std::to_string(expected["score_threshold"].get<double>()) +
                                        " --top-k 1024 --device reference --out " + out.string(),
                                    dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Json report = read_json(out / "report.json");
  EXPECT_EQ(report["detections"].get<int>(), static_cast<int>(expected["detections"].size()));
  EXPECT_NEAR(report["map50"].get<double>(), 1.0, 1e-9);
  EXPECT_NEAR(report["map50_95"].get<double>(), 1.0, 1e-9);
  EXPECT_TRUE(fs::exists(out / "montage.jpg"));

  // In tiles: eval-det runs the detector as detect does, so scoring detect's output for
  // the same tiles gives the same report.
  const std::string score = " --score 0.05 --device reference --tile 160";
  const fs::path dets = dir / "dets.json";
  RunResult detect = run_flexsight("detect " + (data / "rgb" / "000001.png").string() + " --model " +
                                       tiny_ssd_model() + score + " -o " + dets.string(),
                                   dir);
  ASSERT_EQ(detect.exit_code, 0) << detect.err;
  EXPECT_NE(detect.err.find("tiles of 160 px, stride 120 px"), std::string::npos) << detect.err;
  RunResult tiled = run_flexsight("eval-det " + data.string() + " --model " + tiny_ssd_model() + score +
                                      " --out " + (dir / "tiled").string(),
                                  dir);
  ASSERT_EQ(tiled.exit_code, 0) << tiled.err;
  RunResult scored = run_flexsight("eval-det " + data.string() + " --results " + dets.string() + " --out " +
                                       (dir / "scored").string(),
                                   dir);
  ASSERT_EQ(scored.exit_code, 0) << scored.err;
  const Json from_tiles = read_json(dir / "tiled" / "report.json");
  const Json from_detect = read_json(dir / "scored" / "report.json");
  EXPECT_EQ(from_tiles["detections_format"], "model run by eval-det, tiles of 160 px (stride 120)");
  EXPECT_GT(from_tiles["detections"].get<int>(), 0);
  EXPECT_EQ(from_tiles["detections"], from_detect["detections"]);
  EXPECT_EQ(from_tiles["map50"], from_detect["map50"]);
  EXPECT_EQ(from_tiles["class_agnostic"], from_detect["class_agnostic"]);
  EXPECT_EQ(from_tiles["by_size"], from_detect["by_size"]);
  fs::remove_all(dir);
}
