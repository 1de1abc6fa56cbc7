#pragma once
// Evaluation reports: one Markdown table and one JSON document per run.
#include <string>
#include <vector>

#include "host/eval/confidence_depth_metrics.h"
#include "host/eval/metrics.h"

namespace flexsight {

struct SceneReport {
  std::string name;
  int width = 0;
  int height = 0;
  int ndisp = 0;
  SceneScores scores;
  ConfidentStats confident;  // when a confidence map was at hand
  DepthStats depth;          // when the scene has a calibration
  double seconds = 0;  // matcher wall time, 0 when results were read from files
  std::string matcher;  // the path that matched it ("reference path", ...); empty for files
};

// One matcher parameter of a run, as the command line spells it.
struct ReportParameter {
  std::string name;  // option name without dashes, e.g. "window-step"
  std::string value;
  bool is_default = true;
};

struct EvalReport {
  std::string dataset_root;
  std::string method;      // "ppms", "pms", or "files:<folder>"
  std::string matcher;     // where it ran ("OpenCL path on #0 ...", OpenCV's settings); may be empty
  std::vector<ReportParameter> parameters;  // every parameter of the run; none for files
  std::string conventions; // one sentence: resolution, masks, invalid = bad
  std::vector<SceneReport> scenes;
  ErrorStats average_nonocc() const;
  ErrorStats average_all() const;
  double average_seconds() const;
};

std::string to_markdown(const EvalReport& report);
std::string to_json(const EvalReport& report);

}  // namespace flexsight
