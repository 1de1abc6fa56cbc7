// Evaluation reports (host/eval/report.h): averages, the Markdown table and the JSON
// document, read back by nlohmann::json.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "host/eval/report.h"

namespace flexsight {
namespace {

using Json = nlohmann::json;

// ---- reports ---------------------------------------------------------------------

EvalReport sample_report() {
  EvalReport report;
  report.dataset_root = "data/\"quoted\"\\path";
  report.method = "ppms";
  report.matcher = "reference path";
  report.parameters = {{"window", "35", true}, {"window-step", "3", false},
                       {"gamma-distance", "inf", false}};
  report.conventions = "test conventions";
  SceneReport a;
  a.name = "Adirondack";
  a.width = 718;
  a.height = 496;
  a.ndisp = 73;
  a.seconds = 12.5;
  a.scores.all.bad_percent = {40, 30, 20, 15, 10};
  a.scores.all.avg_error = 2.25;
  a.scores.all.density_percent = 100;
  a.scores.all.evaluated = 300000;
  a.scores.nonocc = a.scores.all;
  a.scores.nonocc.bad_percent[2] = 12.5;
  SceneReport b = a;
  b.name = "Motor\tcycle";
  b.seconds = 7.5;
  b.scores.all.bad_percent[2] = 10;
  b.scores.nonocc.bad_percent[2] = 7.5;
  report.scenes = {a, b};
  return report;
}

TEST(Report, AveragesAreUnweightedMeans) {
  const EvalReport report = sample_report();
  EXPECT_DOUBLE_EQ(report.average_all().bad_percent[2], 15.0);     // (20 + 10) / 2
  EXPECT_DOUBLE_EQ(report.average_nonocc().bad_percent[2], 10.0);  // (12.5 + 7.5) / 2
  EXPECT_DOUBLE_EQ(report.average_seconds(), 10.0);
}

TEST(Report, MarkdownHasScenesNumbersAndConventions) {
  const std::string markdown = to_markdown(sample_report());
  for (const char* text : {"Adirondack", "Motor", "average", "test conventions", "ppms",
                           "bad 0.5", "bad 2", "bad 4", "avg err", "density", "time",
                           "12.50", "20.00", "15.00", "10.00", "2.250", "718x496"}) {
    EXPECT_NE(markdown.find(text), std::string::npos) << text << "\n" << markdown;
  }
  // Where it ran, and the parameters that differ from the defaults, as options.
  EXPECT_NE(markdown.find("- Matcher: reference path"), std::string::npos) << markdown;
  EXPECT_NE(markdown.find("`--window-step 3 --gamma-distance inf`, the defaults otherwise"),
            std::string::npos)
      << markdown;
  EXPECT_EQ(markdown.find("--window 35"), std::string::npos) << markdown;
  // Both regions are tabulated.
  EXPECT_NE(markdown.find("## all"), std::string::npos);
  EXPECT_NE(markdown.find("## nonocc"), std::string::npos);
}

TEST(Report, JsonParsesAndHoldsTheNumbers) {
  const std::string text = to_json(sample_report());
  EXPECT_NE(text.find("\"bad_2\""), std::string::npos);
  const Json json = Json::parse(text);
  EXPECT_EQ(json.at("dataset_root").get<std::string>(), "data/\"quoted\"\\path");
  EXPECT_EQ(json.at("method").get<std::string>(), "ppms");
  EXPECT_EQ(json.at("matcher").get<std::string>(), "reference path");
  ASSERT_EQ(json.at("parameters").size(), 3u);  // every one, defaults included
  EXPECT_EQ(json.at("parameters").at("window").get<std::string>(), "35");
  EXPECT_EQ(json.at("parameters").at("gamma-distance").get<std::string>(), "inf");
  ASSERT_EQ(json.at("scenes").size(), 2u);
  const Json& a = json.at("scenes").at(0);
  EXPECT_EQ(a.at("name").get<std::string>(), "Adirondack");
  EXPECT_EQ(a.at("width").get<double>(), 718);
  EXPECT_EQ(a.at("ndisp").get<double>(), 73);
  EXPECT_DOUBLE_EQ(a.at("seconds").get<double>(), 12.5);
  EXPECT_DOUBLE_EQ(a.at("all").at("bad_0.5").get<double>(), 40);
  EXPECT_DOUBLE_EQ(a.at("all").at("bad_2").get<double>(), 20);
  EXPECT_DOUBLE_EQ(a.at("nonocc").at("bad_2").get<double>(), 12.5);
  EXPECT_DOUBLE_EQ(a.at("all").at("avg_error").get<double>(), 2.25);
  EXPECT_DOUBLE_EQ(a.at("all").at("density").get<double>(), 100);
  EXPECT_EQ(a.at("all").at("evaluated").get<double>(), 300000);
  EXPECT_EQ(json.at("scenes").at(1).at("name").get<std::string>(), "Motor\tcycle");  // escaped and restored
  EXPECT_DOUBLE_EQ(json.at("average").at("all").at("bad_2").get<double>(), 15);
  EXPECT_DOUBLE_EQ(json.at("average").at("nonocc").at("bad_2").get<double>(), 10);
  EXPECT_DOUBLE_EQ(json.at("average").at("seconds").get<double>(), 10);
}

TEST(Report, JsonOfEmptyReportParses) {
  EvalReport report;
  const Json json = Json::parse(to_json(report));
  EXPECT_TRUE(json.at("scenes").empty());
  EXPECT_EQ(json.at("average").at("all").at("evaluated").get<double>(), 0);
}

}  // namespace
}  // namespace flexsight
