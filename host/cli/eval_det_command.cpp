// flexsight eval-det: scores detections against the ground truth of a BOP or COCO data
// set (VOC and COCO average precision) and writes a Markdown and a JSON report, the
// precision-recall curves and a montage of the first images.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "host/cli/arguments.h"
#include "host/cli/backend.h"
#include "host/cli/commands.h"
#include "host/cli/tile_option.h"
#include "host/dataset/dataset_files.h"
#include "host/detect/detector_model.h"
#include "host/detect/ssd_detector.h"
#include "host/eval/detection_ground_truth.h"
#include "host/eval/detection_breakdown.h"
#include "host/eval/detection_metrics.h"
#include "host/eval/detection_pictures.h"
#include "host/eval/detection_report.h"
#include "host/eval/detection_results_reader.h"
#include "host/eval/detector_evaluation.h"
#include "host/io/image_io.h"
#include "host/io/input_error.h"
#include "host/io/report_text.h"
#include "host/io/staged_folder.h"

namespace flexsight {

namespace {

namespace fs = std::filesystem;

constexpr int kDefaultMontageImages = 16;
constexpr int kMaxMontageImages = 256;

// Scores below this are dropped before NMS when eval-det runs the model itself: low
// enough that the precision-recall curve reaches the model's full recall (the TF OD API
// evaluates at 1e-8; 0.01 keeps NMS short and changes AP by less than 0.001 in our runs).
constexpr float kEvalScoreThreshold = 0.01f;

struct EvalDetOptions {
  std::string dataset;
  std::string results;  // the detections file (--results)
  std::string model;    // or the detector run on every image (--model, or the shipped one)
  SsdDetectorOptions detector;
  BackendOptions backend;
  int threads = 0;
  bool quiet = false;
  std::string out;
  bool overwrite = false;
  double iou_threshold = 0.5;
  int montage = kDefaultMontageImages;
  int tile = 0;
  double recall_score = 0.3;
  double min_visible = 0;
};

void print_help() {
  std::cout
      << "usage: flexsight eval-det DATASET [--model M.onnx | --results DETS.json] --out DIR [options]\n"
         "  DATASET               a COCO instances file, a folder with coco_instances.json\n"
         "                        (flexsight synth's output), or a BOP scene or split folder\n"
         "                        (boxes: bbox_visib of scene_gt_info.json)\n"
         "  --model M.onnx        run this detector (flexsight detect's) on every image; the\n"
         "                        default when --results is not given, with the shipped model\n"
         "                        (models/tless-ssd, or FLEXSIGHT_DETECT_MODEL)\n"
         "  --score S             with --model: lowest score kept (default 0.01, so that the\n"
         "                        curves reach the model's full recall)\n"
         "  --top-k K             with --model: candidates per class into NMS (default 100)\n"
         "  --threads N           with --model: OpenCV's threads (0 = all cores, default)\n"
      << tile_option_help(24)
      << "                        (with --model)\n"
         "  --quiet               no progress line\n"
         "  --results DETS.json   or score these detections: a JSON list of COCO results\n"
         "                        {image_id, category_id, bbox [x, y, w, h], score} with the\n"
         "                        COCO file's image ids, or BOP 2D detection results\n"
         "                        {scene_id, image_id = im_id, category_id = obj_id, bbox,\n"
         "                        score, time}; boxes in pixels, scores in [0, 1]\n"
         "  --out DIR             output folder (new or empty): report.md, report.json,\n"
         "                        pr_curve.png, montage.jpg\n"
         "  --overwrite           replace DIR when it is not empty\n"
         "  --iou-threshold T     IoU of a match for the VOC AP and the curves (default 0.5;\n"
         "                        map50 is at 0.5 and the COCO APs at 0.50:0.05:0.95 whatever T)\n"
         "  --montage N           the first N images in montage.jpg (default 16, 0 = none)\n"
         "  --recall-score S      the score of the recall by part size (default 0.3, detect's\n"
         "                        --score); recall at any score is reported too\n"
         "  --min-visible F       BOP folders: parts less visible than F (visib_fract, 0..1)\n"
         "                        are crowd regions, neither found nor missed (default 0)\n"
         "With --model the post-processing (decoding, NMS) runs on --device:\n"
      << backend_options_help();
}

double parse_iou_threshold(const std::string& text) {
  try {
    std::size_t used = 0;
    const double value = std::stod(text, &used);
    if (used == text.size() && value > 0 && value <= 1) return value;
  } catch (const std::exception&) {
    // reported below, with the option's name
  }
  throw InputError("option --iou-threshold", "expected a number in (0, 1], got '" + text + "'");
}

int parse_montage(const std::string& text) {
  try {
    std::size_t used = 0;
    const int value = std::stoi(text, &used);
    if (used == text.size() && value >= 0 && value <= kMaxMontageImages) return value;
  } catch (const std::exception&) {
    // reported below, with the option's name
  }
  throw InputError("option --montage", "expected a whole number from 0 to " +
                                           std::to_string(kMaxMontageImages) + ", got '" + text + "'");
}

EvalDetOptions parse_options(std::vector<std::string> args) {
  EvalDetOptions options;
  options.results = take_option(args, "--results");
  options.out = take_option(args, "--out");
  options.overwrite = take_flag(args, "--overwrite");
  const std::string threshold = take_option(args, "--iou-threshold");
  if (!threshold.empty()) options.iou_threshold = parse_iou_threshold(threshold);
  const std::string montage = take_option(args, "--montage");
  if (!montage.empty()) options.montage = parse_montage(montage);
  options.model = take_option(args, "--model");
  const double score = take_number_option(args, "--score", kEvalScoreThreshold);
  if (!(score >= 0.0 && score <= 1.0)) {
    throw InputError("option --score", "must lie in [0, 1], got " + std::to_string(score));
  }
  options.detector.score_threshold = static_cast<float>(score);
  const std::string top_k = take_option(args, "--top-k");
  if (!top_k.empty()) {
    options.detector.top_k_per_class = static_cast<int>(parse_whole_number("--top-k", top_k, 1, 1024));
  }
  const std::string threads = take_option(args, "--threads");
  if (!threads.empty()) {
    options.threads = static_cast<int>(parse_whole_number("--threads", threads, 0, 1024));
  }
  options.tile = take_tile_option(args);
  options.recall_score = take_number_option(args, "--recall-score", options.recall_score);
  if (!(options.recall_score >= 0.0 && options.recall_score <= 1.0)) {
    throw InputError("option --recall-score", "must lie in [0, 1], got " + std::to_string(options.recall_score));
  }
  options.min_visible = take_number_option(args, "--min-visible", options.min_visible);
  if (!(options.min_visible >= 0.0 && options.min_visible <= 1.0)) {
    throw InputError("option --min-visible", "must lie in [0, 1], got " + std::to_string(options.min_visible));
  }
  options.quiet = take_flag(args, "--quiet");
  options.backend = take_backend_options(args);
  reject_unknown_options(args);
  if (args.size() != 1) {
    throw InputError("DATASET", args.empty() ? "missing (see flexsight eval-det --help)"
                                             : "expected one data set, got " +
                                                   std::to_string(args.size()) + " arguments");
  }
  options.dataset = args.front();
  if (!options.results.empty() && !options.model.empty()) {
    throw InputError("option --model", "give either --model or --results, not both");
  }
  if (options.out.empty()) throw InputError("option --out", "an output folder is required");
  if (options.tile > 0 && !options.results.empty()) {
    throw InputError("option --tile", "runs the detector in tiles; it has no meaning with --results");
  }
  return options;
}

// The detections to score, one list per image of `truth`: a results file, or the
// detector run on each image.
DetectionResults collect_detections(const EvalDetOptions& options, const DetectionGroundTruth& truth) {
  if (!options.results.empty()) return read_detection_results(options.results, truth);
  DetectorRunOptions run;
  run.detector = options.detector;
  run.backend = options.backend;
  run.threads = options.threads;
  run.quiet = options.quiet;
  run.tile = options.tile;
  return run_detector(resolve_detector_model_path(options.model), truth, run);
}

// The class-agnostic and by-size figures as a text table (report.md has them too).
std::string size_table(const DetectionBreakdown& b) {
  const std::string score = threshold_label(b.recall_score);
  std::string text = "class-agnostic AP@0.5 " + fraction_text(b.agnostic.ap50) + ", AP@[.5:.95] " +
                     fraction_text(b.agnostic_coco_ap) + "; by part size (sqrt of the box's area), recall at IoU 0.5:\n";
  char line[200];
  std::snprintf(line, sizeof line, "%-8s %6s %8s %9s %9s %10s %9s %9s\n", "size px", "truth", "mAP@0.5",
                ("rec>=" + score).c_str(), "rec any", "agn AP@.5", ("agn>=" + score).c_str(), "agn any");
  text += line;
  const auto row = [&](const std::string& label, const MatchFigures& c, const MatchFigures& a) {
    std::snprintf(line, sizeof line, "%-8s %6d %8s %9s %9s %10s %9s %9s\n", label.c_str(), c.ground_truth,
                  fraction_text(c.ap50).c_str(), fraction_text(c.recall_at_score).c_str(),
                  fraction_text(c.recall_any).c_str(), fraction_text(a.ap50).c_str(),
                  fraction_text(a.recall_at_score).c_str(), fraction_text(a.recall_any).c_str());
    text += line;
  };
  row("all", b.per_class, b.agnostic);
  for (const SizeFigures& size : b.sizes) row(size.bin.label, size.per_class, size.agnostic);
  return text;
}

}  // namespace

int run_eval_det_command(std::vector<std::string> args) {
  if (const auto code = usage_exit_code(args, print_help)) return *code;
  const EvalDetOptions options = parse_options(std::move(args));

  // Every input is read and checked before anything is written.
  const DetectionGroundTruth truth(options.dataset, options.min_visible);
  std::vector<std::vector<TruthBox>> truth_boxes;
  bool any_truth = false;
  for (const DetectionImage& image : truth.images()) {
    truth_boxes.push_back(image.truth);
    for (const TruthBox& box : image.truth) any_truth = any_truth || !box.crowd;
  }
  if (!any_truth) {
    throw InputError(truth.source(), "has no ground-truth box (no visible object): nothing to score");
  }
  // The detector reads every image; a results file needs only the montage's first ones.
  const std::vector<cv::Size> sizes =
      truth.check_images(options.results.empty() ? truth.images().size() : static_cast<std::size_t>(options.montage));
  if (options.tile > 0) {  // --tile runs the detector: every image was required above
    for (std::size_t i = 0; i < sizes.size(); ++i) {
      check_tile_fits(options.tile, sizes[i], "image " + std::to_string(i + 1) + " of " + truth.source());
    }
  }
  // The output folder is checked (and its staging folder made) before the detector runs.
  StagedFolder staged(options.out, options.overwrite, "--out");
  const DetectionResults detections = collect_detections(options, truth);
  DetectionEvalOptions eval_options;
  eval_options.iou_threshold = options.iou_threshold;
  DetectionReport report;
  report.dataset = truth.source();
  report.dataset_format = truth.format() == DetectionGroundTruth::Format::coco ? "COCO" : "BOP";
  report.detections = detections.source;
  report.detections_format = detections.format;
  std::vector<DetectionCategory> categories = truth.categories();
  categories.insert(categories.end(), detections.extra_categories.begin(), detections.extra_categories.end());
  std::sort(categories.begin(), categories.end(),
            [](const DetectionCategory& a, const DetectionCategory& b) { return a.id < b.id; });
  report.scores = evaluate_detections(truth_boxes, detections.per_image, categories, eval_options);
  DetectionBreakdownOptions breakdown_options;
  breakdown_options.recall_score = options.recall_score;
  report.breakdown = evaluate_breakdown(truth_boxes, detections.per_image, categories, breakdown_options);
  const cv::Mat curves = draw_pr_curves(report.scores);
  const cv::Mat montage = draw_detection_montage(montage_images(truth, detections, options.montage));

  // The folder appears whole or not at all.
  const fs::path dir(staged.path());
  dataset_files::write_text((dir / "report.md").string(), to_markdown(report));
  dataset_files::write_text((dir / "report.json").string(), to_json(report));
  write_image((dir / "pr_curve.png").string(), curves);
  if (!montage.empty()) write_image((dir / "montage.jpg").string(), montage);
  staged.commit();

  const DetectionScores& s = report.scores;
  std::cout << "eval-det: " << s.images << " images, " << s.ground_truth << " boxes, "
            << s.detections << " detections: mAP@0.5 " << fraction_text(s.map50)
            << " (VOC), mAP@[.5:.95] " << fraction_text(s.map50_95) << ", AP50 "
            << fraction_text(s.ap50_coco) << ", AP75 " << fraction_text(s.ap75) << " -> "
            << staged.target() << "\n";
  std::cout << size_table(report.breakdown);
  return 0;
}

}  // namespace flexsight
