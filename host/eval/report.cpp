#include "host/eval/report.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "host/io/report_text.h"

namespace flexsight {

namespace {

constexpr int kPercentDecimals = 2;  // Markdown
constexpr int kErrorDecimals = 3;    // Markdown
constexpr int kSecondsDecimals = 2;  // Markdown
constexpr int kJsonDecimals = 6;     // JSON keeps more for scripts that compare runs

std::string markdown_header() {
  std::string header = "| scene | size | ndisp |";
  std::string rule = "|---|---|---:|";
  for (double t : kBadThresholds) {
    header += " bad " + threshold_label(t) + " (%) |";
    rule += "---:|";
  }
  header += " avg err (px) | density (%) | time (s) |";
  rule += "---:|---:|---:|";
  return header + "\n" + rule + "\n";
}

std::string markdown_stats(const ErrorStats& stats, double seconds) {
  std::string cells;
  for (double percent : stats.bad_percent) cells += " " + fixed_decimals(percent, kPercentDecimals) + " |";
  cells += " " + fixed_decimals(stats.avg_error, kErrorDecimals, "n/a") + " |";
  cells += " " + fixed_decimals(stats.density_percent, kPercentDecimals) + " |";
  // Results read from files have no matcher time.
  cells += " " + (seconds > 0 ? fixed_decimals(seconds, kSecondsDecimals) : std::string("-")) + " |";
  return cells;
}

std::string markdown_table(const EvalReport& report, const char* region,
                           ErrorStats SceneScores::*select, const ErrorStats& mean) {
  std::string table = std::string("## ") + region + "\n\n" + markdown_header();
  for (const SceneReport& scene : report.scenes) {
    table += "| " + markdown_cell(scene.name) + " | " + std::to_string(scene.width) + "x" +
             std::to_string(scene.height) + " | " + std::to_string(scene.ndisp) + " |" +
             markdown_stats(scene.scores.*select, scene.seconds) + "\n";
  }
  table += "| **average** | | |" + markdown_stats(mean, report.average_seconds()) + "\n";
  return table;
}

// Mean over the scenes where `value` is finite; NaN when there is none.
template <typename Value>
double mean_available(const std::vector<SceneReport>& scenes, Value value) {
  double sum = 0;
  int n = 0;
  for (const SceneReport& scene : scenes) {
    const double v = value(scene);
    if (!std::isfinite(v)) continue;
    sum += v;
    ++n;
  }
  return n ? sum / n : std::nan("");
}

std::string cell(double value, int decimals) {
  return fixed_decimals(value, decimals, "-");
}

// Confidence thresholds and depth error, when any scene has them.
std::string markdown_confidence_and_depth(const EvalReport& report) {
  bool any = false;
  for (const SceneReport& s : report.scenes) any = any || s.confident.available || s.depth.available;
  if (!any) return "";
  std::string header = "| scene |", rule = "|---|";
  for (float t : kConfidenceThresholds) {
    header += " C>=" + threshold_label(t) + " density (%) | C>=" + threshold_label(t) + " bad 2 (%) |";
    rule += "---:|---:|";
  }
  header += " sparsification AUC, bad 2 (%) | optimal AUC (%) |";
  rule += "---:|---:|";
  header += " median abs depth error, all (mm) | same, C>=" +
            threshold_label(kDepthConfidenceThreshold) + " (mm) |";
  rule += "---:|---:|";
  std::string text =
      "## confidence and depth\n\n"
      "Pixels with ground truth whose confidence (host/stereo/confidence_map.h) passes a "
      "threshold: their share and their bad-2 (all pixels). Sparsification AUC: the bad-2 of "
      "the most confident 5, 10, ..., 100 % of them, averaged (lower is better; optimal: ranked "
      "by the true error). Depth error: our depth against the "
      "depth of the ground-truth disparity through the scene's own calibration; a pixel "
      "without a result counts as an infinite error.\n\n";
  text += header + "\n" + rule + "\n";
  auto row = [&](const std::string& name, auto density, auto bad2, double auc, double optimal,
                 double all, double conf) {
    std::string line = "| " + name + " |";
    for (size_t t = 0; t < kConfidenceThresholds.size(); ++t) {
      line += " " + cell(density(t), kPercentDecimals) + " | " + cell(bad2(t), kPercentDecimals) + " |";
    }
    line += " " + cell(auc, kPercentDecimals) + " | " + cell(optimal, kPercentDecimals) + " |";
    return line + " " + cell(all, 1) + " | " + cell(conf, 1) + " |\n";
  };
  const double nan = std::nan("");
  for (const SceneReport& s : report.scenes) {
    text += row(markdown_cell(s.name),
                [&](size_t t) { return s.confident.available ? s.confident.density_percent[t] : nan; },
                [&](size_t t) { return s.confident.available ? s.confident.bad2_percent[t] : nan; },
                s.confident.available ? s.confident.sparsification_auc_percent : nan,
                s.confident.available ? s.confident.optimal_auc_percent : nan,
                s.depth.available ? s.depth.median_abs_mm_all : nan,
                s.depth.available ? s.depth.median_abs_mm_confident : nan);
  }
  const auto& scenes = report.scenes;
  text += row(
      "**average**",
      [&](size_t t) {
        return mean_available(scenes, [&](const SceneReport& s) {
          return s.confident.available ? s.confident.density_percent[t] : nan;
        });
      },
      [&](size_t t) {
        return mean_available(scenes, [&](const SceneReport& s) {
          return s.confident.available ? s.confident.bad2_percent[t] : nan;
        });
      },
      mean_available(scenes, [&](const SceneReport& s) {
        return s.confident.available ? s.confident.sparsification_auc_percent : nan;
      }),
      mean_available(scenes, [&](const SceneReport& s) {
        return s.confident.available ? s.confident.optimal_auc_percent : nan;
      }),
      mean_available(scenes, [&](const SceneReport& s) { return s.depth.available ? s.depth.median_abs_mm_all : nan; }),
      mean_available(scenes, [&](const SceneReport& s) {
        return s.depth.available ? s.depth.median_abs_mm_confident : nan;
      }));
  return text;
}

// ---- JSON ------------------------------------------------------------------------
//
// Written here rather than through nlohmann::json (which the other reports use) because
// report.json's bytes are a fixed format that scripts compare between runs: every score has
// six decimals ("12.500000"), thresholds are short labels (0.5, 2), and the confidence and
// depth blocks sit on one line each. nlohmann writes the shortest round-trip number
// ("12.5") and one element per line, so it would change every file. The number rule lives in
// json_number alone.

std::string json_string(const std::string& text) {
  std::string out = "\"";
  for (unsigned char c : text) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      default:
        if (c < 0x20) {
          char buffer[8];
          std::snprintf(buffer, sizeof buffer, "\\u%04x", c);
          out += buffer;
        } else {
          out += static_cast<char>(c);  // UTF-8 passes through unchanged
        }
    }
  }
  return out + "\"";
}

// JSON has no NaN or infinity; such a value can only come from a bug, and null keeps
// the document parseable while making the problem visible.
std::string json_number(double value, int decimals = kJsonDecimals) {
  return fixed_decimals(value, decimals, "null");
}

std::string json_stats(const ErrorStats& stats, const std::string& indent) {
  std::ostringstream out;
  out << "{\n";
  for (std::size_t t = 0; t < kBadThresholds.size(); ++t) {
    out << indent << "  \"bad_" << threshold_label(kBadThresholds[t])
        << "\": " << json_number(stats.bad_percent[t]) << ",\n";
  }
  out << indent << "  \"avg_error\": " << json_number(stats.avg_error) << ",\n";
  out << indent << "  \"density\": " << json_number(stats.density_percent) << ",\n";
  out << indent << "  \"evaluated\": " << stats.evaluated << "\n";
  out << indent << "}";
  return out.str();
}

std::string json_scene(const SceneReport& scene) {
  std::ostringstream out;
  out << "    {\n"
      << "      \"name\": " << json_string(scene.name) << ",\n"
      << "      \"width\": " << scene.width << ",\n"
      << "      \"height\": " << scene.height << ",\n"
      << "      \"ndisp\": " << scene.ndisp << ",\n"
      << "      \"seconds\": " << json_number(scene.seconds) << ",\n"
      << "      \"matcher\": " << json_string(scene.matcher) << ",\n"
      << "      \"all\": " << json_stats(scene.scores.all, "      ") << ",\n"
      << "      \"nonocc\": " << json_stats(scene.scores.nonocc, "      ");
  if (scene.confident.available) {
    out << ",\n      \"confident\": {\"thresholds\": [";
    for (size_t t = 0; t < kConfidenceThresholds.size(); ++t) {
      out << (t ? ", " : "") << threshold_label(kConfidenceThresholds[t]);
    }
    out << "], \"density\": [";
    for (size_t t = 0; t < kConfidenceThresholds.size(); ++t) {
      out << (t ? ", " : "") << json_number(scene.confident.density_percent[t]);
    }
    out << "], \"bad2\": [";
    for (size_t t = 0; t < kConfidenceThresholds.size(); ++t) {
      out << (t ? ", " : "") << json_number(scene.confident.bad2_percent[t]);
    }
    out << "], \"sparsification_auc_bad2\": "
        << json_number(scene.confident.sparsification_auc_percent)
        << ", \"optimal_auc_bad2\": " << json_number(scene.confident.optimal_auc_percent);
    auto curve = [&](const char* name, const auto& values) {
      out << ", \"" << name << "\": [";
      for (size_t k = 0; k < values.size(); ++k) out << (k ? ", " : "") << json_number(values[k]);
      out << "]";
    };
    curve("sparsification_curve_bad2", scene.confident.sparsification_curve_percent);
    curve("optimal_curve_bad2", scene.confident.optimal_curve_percent);
    out << "}";
  }
  if (scene.depth.available) {
    out << ",\n      \"depth_mm\": {\"median_abs_all\": "
        << json_number(scene.depth.median_abs_mm_all) << ", \"median_abs_confident\": "
        << json_number(scene.depth.median_abs_mm_confident) << "}";
  }
  out << "\n    }";
  return out.str();
}

ErrorStats average_of(const std::vector<SceneReport>& scenes, ErrorStats SceneScores::*select) {
  std::vector<ErrorStats> stats;
  for (const SceneReport& scene : scenes) stats.push_back(scene.scores.*select);
  return average(stats);
}

}  // namespace

ErrorStats EvalReport::average_nonocc() const { return average_of(scenes, &SceneScores::nonocc); }

ErrorStats EvalReport::average_all() const { return average_of(scenes, &SceneScores::all); }

double EvalReport::average_seconds() const {
  if (scenes.empty()) return 0;
  double sum = 0;
  for (const SceneReport& scene : scenes) sum += scene.seconds;
  return sum / static_cast<double>(scenes.size());
}

namespace {

// The parameters that differ from the defaults, as options; the JSON has every one.
std::string markdown_parameters(const EvalReport& report) {
  std::string changed;
  for (const ReportParameter& parameter : report.parameters) {
    if (parameter.is_default) continue;
    changed += (changed.empty() ? "`--" : " --") + parameter.name + " " + parameter.value;
  }
  return changed.empty() ? "the defaults (every value in report.json)"
                         : changed + "`, the defaults otherwise (every value in report.json)";
}

}  // namespace

std::string to_markdown(const EvalReport& report) {
  std::string text = "# FlexSight evaluation\n\n";
  text += "- Dataset: `" + report.dataset_root + "`\n";
  text += "- Method: " + report.method + "\n";
  if (!report.matcher.empty()) text += "- Matcher: " + report.matcher + "\n";
  if (!report.parameters.empty()) text += "- Parameters: " + markdown_parameters(report) + "\n";
  text += "- Conventions: " + report.conventions + "\n\n";
  text += markdown_table(report, "all", &SceneScores::all, report.average_all());
  text += "\n";
  text += markdown_table(report, "nonocc", &SceneScores::nonocc, report.average_nonocc());
  const std::string extra = markdown_confidence_and_depth(report);
  if (!extra.empty()) text += "\n" + extra;
  return text;
}

std::string to_json(const EvalReport& report) {
  std::ostringstream out;
  out << "{\n"
      << "  \"dataset_root\": " << json_string(report.dataset_root) << ",\n"
      << "  \"method\": " << json_string(report.method) << ",\n"
      << "  \"matcher\": " << json_string(report.matcher) << ",\n"
      << "  \"parameters\": {";
  for (std::size_t i = 0; i < report.parameters.size(); ++i) {
    out << (i ? ", " : "") << json_string(report.parameters[i].name) << ": "
        << json_string(report.parameters[i].value);
  }
  out << "},\n"
      << "  \"conventions\": " << json_string(report.conventions) << ",\n"
      << "  \"thresholds\": [";
  for (std::size_t t = 0; t < kBadThresholds.size(); ++t) {
    out << (t ? ", " : "") << threshold_label(kBadThresholds[t]);
  }
  out << "],\n  \"scenes\": [";
  for (std::size_t i = 0; i < report.scenes.size(); ++i) {
    out << (i ? ",\n" : "\n") << json_scene(report.scenes[i]);
  }
  out << (report.scenes.empty() ? "],\n" : "\n  ],\n");
  out << "  \"average\": {\n"
      << "    \"seconds\": " << json_number(report.average_seconds()) << ",\n"
      << "    \"all\": " << json_stats(report.average_all(), "    ") << ",\n"
      << "    \"nonocc\": " << json_stats(report.average_nonocc(), "    ") << "\n"
      << "  }\n"
      << "}\n";
  return out.str();
}

}  // namespace flexsight
