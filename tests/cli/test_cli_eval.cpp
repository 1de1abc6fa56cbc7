// The eval command (host/cli/commands.h), end to end on small trees the tests write
// themselves: scores of given result files, and the matcher run by the command.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "host/cli/commands.h"
#include "host/eval/dataset.h"
#include "host/eval/report.h"
#include "host/io/input_error.h"
#include "host/io/pfm.h"
#include "host/stereo/stereo_params.h"
#include "tests/eval/dataset_test_support.h"

namespace flexsight {
namespace {

using namespace dataset_test_support;
using Json = nlohmann::json;

// ---- the eval command, end to end ------------------------------------------------

// Alpha (4x2), threshold results by hand. GT 8 everywhere except (3,1) unknown.
//   result row 0: 8 (err 0), 9 (1), 11 (3), NaN (none)
//   result row 1: 8.5 (0.5), 2 (6, occluded: mask 128), 8 (0), 8 (no GT)
// all:    7 evaluated, 6 with a result, errors 0 1 3 0.5 6 0 (sum 10.5)
//         bad>0.5: 1 3 6 + none = 4/7; >1: 3 6 + none = 3/7; >2: 3/7; >3: 6 + none = 2/7;
//         >4: 2/7; avg 10.5/6 = 1.75; density 6/7
// nonocc: 6 evaluated (without (1,1)), 5 with a result, errors 0 1 3 0.5 0 (sum 4.5)
//         bad>0.5: 1 3 + none = 3/6; >1: 3 + none = 2/6; >2: 2/6; >3: 1/6; >4: 1/6;
//         avg 4.5/5 = 0.9; density 5/6
// Beta (2x2): perfect result: 0% bad, avg 0, density 100.
struct EvalTree {
  TempDir dir;
  fs::path root = dir / "dataset";
  fs::path results = dir / "results";
  fs::path out = dir / "out";

  EvalTree() {
    write_middeval3_scene(root / "Alpha", rows_to_mat({{8, 8, 8, 8}, {8, 8, 8, kInf}}),
                          rows_to_mask({{255, 255, 255, 255}, {255, 128, 255, 0}}), 16);
    write_middeval3_scene(root / "Beta", rows_to_mat({{4, 4}, {4, 4}}),
                          rows_to_mask({{255, 255}, {255, 255}}), 16);
    // Both result layouts: <dir>/<scene>.pfm and a MiddEval3 submission folder.
    write_pfm_by_hand(results / "Alpha.pfm", rows_to_mat({{8, 9, 11, kNaN}, {8.5f, 2, 8, 8}}));
    write_pfm_by_hand(results / "Beta" / "disp0PPMS.pfm", rows_to_mat({{4, 4}, {4, 4}}));
  }

  std::vector<std::string> args(std::vector<std::string> extra = {}) const {
    std::vector<std::string> all = {root.string(), "--results", results.string(), "--out",
                                    out.string()};
    all.insert(all.end(), extra.begin(), extra.end());
    return all;
  }
};

void expect_stats(const Json& stats, const std::array<double, 5>& bad, double avg_error,
                  double density, long evaluated) {
  const char* keys[] = {"bad_0.5", "bad_1", "bad_2", "bad_3", "bad_4"};
  for (int t = 0; t < 5; ++t) EXPECT_NEAR(stats.at(keys[t]).get<double>(), bad[t], 1e-6) << keys[t];
  EXPECT_NEAR(stats.at("avg_error").get<double>(), avg_error, 1e-6);
  EXPECT_NEAR(stats.at("density").get<double>(), density, 1e-6);
  EXPECT_EQ(stats.at("evaluated").get<double>(), evaluated);
}

TEST(EvalCommand, ScoresResultFilesEndToEnd) {
  const EvalTree tree;
  testing::internal::CaptureStdout();
  ASSERT_EQ(run_eval_command(tree.args()), 0);
  const std::string printed = testing::internal::GetCapturedStdout();

  const Json json = Json::parse(read_file(tree.out / "report.json"));
  ASSERT_EQ(json.at("scenes").size(), 2u);
  const Json& alpha = json.at("scenes").at(0);
  EXPECT_EQ(alpha.at("name").get<std::string>(), "Alpha");
  EXPECT_EQ(alpha.at("width").get<double>(), 4);
  EXPECT_EQ(alpha.at("height").get<double>(), 2);
  EXPECT_EQ(alpha.at("ndisp").get<double>(), 16);
  EXPECT_EQ(alpha.at("seconds").get<double>(), 0);
  expect_stats(alpha.at("all"), {400.0 / 7, 300.0 / 7, 300.0 / 7, 200.0 / 7, 200.0 / 7}, 1.75,
               600.0 / 7, 7);
  expect_stats(alpha.at("nonocc"), {50, 100.0 / 3, 100.0 / 3, 100.0 / 6, 100.0 / 6}, 0.9,
               500.0 / 6, 6);
  const Json& beta = json.at("scenes").at(1);
  EXPECT_EQ(beta.at("name").get<std::string>(), "Beta");
  expect_stats(beta.at("all"), {0, 0, 0, 0, 0}, 0, 100, 4);
  // Averages: plain means of Alpha and Beta.
  expect_stats(json.at("average").at("all"), {200.0 / 7, 150.0 / 7, 150.0 / 7, 100.0 / 7, 100.0 / 7},
               0.875, 50 + 300.0 / 7, 6);  // evaluated: (7 + 4) / 2 = 5.5, rounded to 6
  expect_stats(json.at("average").at("nonocc"), {25, 50.0 / 3, 50.0 / 3, 50.0 / 6, 50.0 / 6}, 0.45,
               50 + 250.0 / 6, 5);  // (6 + 4) / 2
  EXPECT_EQ(json.at("method").get<std::string>().rfind("files:", 0), 0u);

  // Pictures at the ground truth's size; no disparity written for read-in results.
  for (const char* file : {"Alpha_disp.png", "Alpha_error.png", "Beta_disp.png", "Beta_error.png"}) {
    const cv::Mat image = cv::imread((tree.out / file).string(), cv::IMREAD_UNCHANGED);
    ASSERT_FALSE(image.empty()) << file;
    EXPECT_EQ(image.type(), CV_8UC3) << file;
  }
  EXPECT_EQ(cv::imread((tree.out / "Alpha_disp.png").string()).size(), cv::Size(4, 2));
  EXPECT_FALSE(fs::exists(tree.out / "Alpha_disp.pfm"));

  // The Markdown table is both printed and saved, with the conventions line.
  const std::string markdown = read_file(tree.out / "report.md");
  EXPECT_EQ(printed, markdown);
  for (const char* text : {"Alpha", "Beta", "57.14", "1.750", "85.71", "average",
                           "pixels without a result count as bad"}) {
    EXPECT_NE(markdown.find(text), std::string::npos) << text;
  }
}

// A result with no disparity at all has no average error: "n/a" and null, not 0.000
// (0.000 would read as a perfect score).
TEST(EvalCommand, AResultWithoutAnyDisparityHasNoAverageError) {
  EvalTree tree;
  write_pfm_by_hand(tree.results / "Beta" / "disp0PPMS.pfm", rows_to_mat({{kNaN, kNaN}, {kNaN, kNaN}}));
  testing::internal::CaptureStdout();
  ASSERT_EQ(run_eval_command(tree.args({"--scenes", "Beta"})), 0);
  const std::string printed = testing::internal::GetCapturedStdout();
  const std::string json_text = read_file(tree.out / "report.json");
  EXPECT_NE(json_text.find("\"avg_error\": null"), std::string::npos) << json_text;
  EXPECT_NE(printed.find("n/a"), std::string::npos) << printed;
  EXPECT_EQ(printed.find("0.000"), std::string::npos) << printed;
}

TEST(EvalCommand, SceneSelectionAndMaxDispColor) {
  const EvalTree tree;
  testing::internal::CaptureStdout();
  ASSERT_EQ(run_eval_command(tree.args({"--scenes", "Beta", "--max-disp-color", "8"})), 0);
  testing::internal::GetCapturedStdout();
  const Json json = Json::parse(read_file(tree.out / "report.json"));
  ASSERT_EQ(json.at("scenes").size(), 1u);
  EXPECT_EQ(json.at("scenes").at(0).at("name").get<std::string>(), "Beta");
  EXPECT_FALSE(fs::exists(tree.out / "Alpha_disp.png"));
  // Disparity 4 of a maximum of 8 is mid-scale: a different colour than 4 of 16.
  const cv::Mat half = cv::imread((tree.out / "Beta_disp.png").string());
  testing::internal::CaptureStdout();
  ASSERT_EQ(run_eval_command(tree.args({"--scenes", "Beta"})), 0);
  testing::internal::GetCapturedStdout();
  const cv::Mat quarter = cv::imread((tree.out / "Beta_disp.png").string());
  EXPECT_NE(half.at<cv::Vec3b>(0, 0), quarter.at<cv::Vec3b>(0, 0));
}

// Runs the command expecting an InputError whose message contains `needle`.
void expect_input_error(const std::vector<std::string>& args, const std::string& needle) {
  testing::internal::CaptureStdout();
  try {
    run_eval_command(args);
    testing::internal::GetCapturedStdout();
    ADD_FAILURE() << "expected InputError mentioning " << needle;
  } catch (const InputError& error) {
    testing::internal::GetCapturedStdout();
    EXPECT_NE(std::string(error.what()).find(needle), std::string::npos) << error.what();
  }
}

TEST(EvalCommand, RejectsBadInput) {
  const EvalTree tree;
  expect_input_error(tree.args({"--scenes", "Alpha,Gamma"}), "Gamma");
  expect_input_error(tree.args({"--bogus"}), "--bogus");
  expect_input_error(tree.args({"--ndisp", "64"}), "--ndisp");
  expect_input_error(tree.args({"--max-disp-color", "-3"}), "--max-disp-color");
  expect_input_error({(tree.dir / "missing").string(), "--out", tree.out.string()}, "missing");
  expect_input_error({tree.results.string(), "--out", tree.out.string()}, tree.results.string());
  expect_input_error({"--out", tree.out.string()}, "DATASET_ROOT");

  // A missing result file is named in the message, and found before any scene is
  // scored (Beta comes after Alpha).
  fs::remove_all(tree.results / "Beta");
  expect_input_error(tree.args(), "Beta.pfm");
  EXPECT_FALSE(fs::exists(tree.out / "Alpha_disp.png"));
  // A result of another size than the ground truth.
  write_pfm_by_hand(tree.results / "Beta.pfm", rows_to_mat({{4, 4}, {4, 4}}));
  write_pfm_by_hand(tree.results / "Alpha.pfm", rows_to_mat({{1, 2}}));
  expect_input_error(tree.args(), "Alpha.pfm");
}

// What the confidence and depth columns of the report should hold for the Tiny scene of
// the test below, restated from their definitions (host/eval/confidence_depth_metrics.h)
// on the maps the command wrote. Every pixel of Tiny has ground truth (4 px). Its
// calib.txt (middlebury_calib) has f = 100 px, a baseline of 100 mm and doffs 0, so
// Z = 100 * 100 / d mm; a pixel without a result (not finite, or d <= 0: no depth) has
// an infinite depth error.
struct ExpectedConfidentDepth {
  double density_at_half = 0;  // percent of the pixels with ground truth with C >= 0.5
  double median_abs_mm_all = 0;
  double median_abs_mm_confident = 0;
};

double median_by_sorting(std::vector<double> values) {
  if (values.empty()) return kNaN;
  std::sort(values.begin(), values.end());
  const std::size_t mid = values.size() / 2;
  return values.size() % 2 ? values[mid] : 0.5 * (values[mid - 1] + values[mid]);
}

ExpectedConfidentDepth confident_depth_by_hand(const cv::Mat& disparity, const cv::Mat& gt,
                                               const cv::Mat& confidence) {
  std::vector<double> all, confident;
  long known = 0, passed = 0;
  for (int y = 0; y < gt.rows; ++y) {
    for (int x = 0; x < gt.cols; ++x) {
      const double z_truth = 100.0 * 100.0 / gt.at<float>(y, x);
      const float d = disparity.at<float>(y, x);
      const double error = std::isfinite(d) && d > 0
                               ? std::abs(100.0 * 100.0 / d - z_truth)
                               : std::numeric_limits<double>::infinity();
      ++known;
      all.push_back(error);
      if (confidence.at<float>(y, x) >= 0.5f) {
        ++passed;
        confident.push_back(error);
      }
    }
  }
  return {100.0 * passed / known, median_by_sorting(all), median_by_sorting(confident)};
}

// The report writes a value that is not finite as null.
void expect_number_or_null(const Json& value, double expected) {
  if (std::isfinite(expected)) {
    // 6 decimals in the JSON; the depth through the calibration agrees to rounding.
    EXPECT_NEAR(value.get<double>(), expected, 1e-5 + 1e-9 * std::abs(expected));
  } else {
    EXPECT_TRUE(value.is_null()) << "expected null for " << expected;
  }
}

TEST(EvalCommand, RunsTheMatcherAndWritesItsDisparity) {
  TempDir dir;
  const fs::path root = dir / "dataset";
  const cv::Mat gt(48, 64, CV_32FC1, cv::Scalar(4));
  write_middeval3_scene(root / "Tiny", gt, cv::Mat(gt.size(), CV_8UC1, cv::Scalar(255)), 16);
  const fs::path out = dir / "out";

  testing::internal::CaptureStdout();
  testing::internal::CaptureStderr();
  const int code = run_eval_command(
      {root.string(), "--out", out.string(), "--threads", "1", "--preset", "fast", "--seed", "5"});
  const std::string progress = testing::internal::GetCapturedStderr();
  testing::internal::GetCapturedStdout();
  ASSERT_EQ(code, 0);
  EXPECT_NE(progress.find("[1/1] Tiny: "), std::string::npos) << progress;

  const cv::Mat disparity = read_pfm((out / "Tiny_disp.pfm").string());
  EXPECT_EQ(disparity.size(), gt.size());
  const Json json = Json::parse(read_file(out / "report.json"));
  EXPECT_GT(json.at("scenes").at(0).at("seconds").get<double>(), 0);
  EXPECT_EQ(json.at("scenes").at(0).at("all").at("evaluated").get<double>(), 64 * 48);
  EXPECT_EQ(json.at("scenes").at(0).at("ndisp").get<double>(), 16);
  EXPECT_TRUE(fs::exists(out / "Tiny_error.png"));
  // The report records how it was made: every parameter (ndisp is the scene's), the
  // preset's among them, and the path that ran.
  StereoParams fast;
  apply_stereo_preset("fast", fast);
  const Json& parameters = json.at("parameters");
  EXPECT_EQ(parameters.at("window-step-finest").get<std::string>(), std::to_string(fast.window_step_finest));
  EXPECT_EQ(parameters.at("iterations-fine").get<std::string>(), std::to_string(fast.iterations_fine));
  EXPECT_EQ(parameters.at("seed").get<std::string>(), "5");
  EXPECT_EQ(parameters.at("threads").get<std::string>(), "1");
  EXPECT_EQ(parameters.at("census-cap").get<std::string>(), "10");
  EXPECT_FALSE(parameters.contains("ndisp"));
  EXPECT_FALSE(json.at("matcher").get<std::string>().empty());
  EXPECT_EQ(json.at("scenes").at(0).at("matcher").get<std::string>(), json.at("matcher").get<std::string>());  // what ran there
  const std::string markdown = read_file(out / "report.md");
  EXPECT_NE(markdown.find("--seed 5"), std::string::npos) << markdown;
  EXPECT_NE(markdown.find("--window-step-finest " + std::to_string(fast.window_step_finest)),
            std::string::npos)
      << markdown;
  EXPECT_EQ(markdown.find("--census-cap"), std::string::npos) << markdown;  // a default

  // The output folder can be scored again as results: same numbers, no matcher time.
  testing::internal::CaptureStdout();
  testing::internal::CaptureStderr();
  const int rescore = run_eval_command(
      {root.string(), "--results", out.string(), "--out", (dir / "out2").string()});
  testing::internal::GetCapturedStderr();
  testing::internal::GetCapturedStdout();
  ASSERT_EQ(rescore, 0);
  const Json again = Json::parse(read_file(dir / "out2" / "report.json"));
  EXPECT_EQ(again.at("scenes").at(0).at("seconds").get<double>(), 0);
  EXPECT_EQ(again.at("scenes").at(0).at("matcher").get<std::string>(), "");  // read from files: no matcher
  EXPECT_EQ(again.at("matcher").get<std::string>(), "");
  EXPECT_TRUE(again.at("parameters").empty());
  for (const char* region : {"all", "nonocc"}) {
    for (const char* key : {"bad_0.5", "bad_1", "bad_2", "avg_error", "density"}) {
      EXPECT_EQ(again.at("scenes").at(0).at(region).at(key).get<double>(), json.at("scenes").at(0).at(region).at(key).get<double>())
          << region << " " << key;
    }
  }
  // The confidence map written beside the disparity is read back with it, and the
  // scene's calib.txt gives the depth error: both reports hold the figures recomputed
  // here from the written maps, and so agree with each other.
  ASSERT_TRUE(fs::exists(out / "Tiny_conf.pfm"));
  const cv::Mat confidence = read_pfm((out / "Tiny_conf.pfm").string());
  ASSERT_EQ(confidence.size(), gt.size());
  const ExpectedConfidentDepth expected = confident_depth_by_hand(disparity, gt, confidence);
  for (const Json* report : {&json, &again}) {
    SCOPED_TRACE(report == &json ? "matcher run" : "read back from files");
    const Json& scene = report->at("scenes").at(0);
    EXPECT_NEAR(scene.at("confident").at("density").at(1).get<double>(), expected.density_at_half, 1e-5);
    expect_number_or_null(scene.at("depth_mm").at("median_abs_all"), expected.median_abs_mm_all);
    expect_number_or_null(scene.at("depth_mm").at("median_abs_confident"),
                          expected.median_abs_mm_confident);
  }
}

}  // namespace
}  // namespace flexsight
