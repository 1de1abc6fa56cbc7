// flexsight eval-det: scores detections against the ground truth of a BOP or COCO data
// set (VOC and COCO average precision) and writes a Markdown and a JSON report, the
// precision-recall curves and a montage of the first images.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "host/cli/arguments.h"
#include "host/cli/commands.h"
#include "host/dataset/dataset_files.h"
#include "host/eval/detection_ground_truth.h"
#include "host/eval/detection_metrics.h"
#include "host/eval/detection_pictures.h"
#include "host/eval/detection_report.h"
#include "host/eval/detection_results_reader.h"
#include "host/io/image_io.h"
#include "host/io/input_error.h"
#include "host/io/staged_folder.h"

namespace flexsight {

namespace {

namespace fs = std::filesystem;

constexpr int kDefaultMontageImages = 16;
constexpr int kMaxMontageImages = 256;

struct EvalDetOptions {
  std::string dataset;
  std::string results;  // the detections file (--results)
  std::string out;
  bool overwrite = false;
  double iou_threshold = 0.5;
  int montage = kDefaultMontageImages;
};

void print_help() {
  std::cout
      << "usage: flexsight eval-det DATASET --results DETS.json --out DIR [options]\n"
         "  DATASET               a COCO instances file, a folder with coco_instances.json\n"
         "                        (flexsight synth's output), or a BOP scene or split folder\n"
         "                        (boxes: bbox_visib of scene_gt_info.json)\n"
         "  --results DETS.json   the detections (required): a JSON list of COCO results\n"
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
         "Running a detector on the data set's images (--model) is not there yet: score its\n"
         "detections written to a file with --results.\n";
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
  if (take_flag(args, "--model")) {
    throw InputError("option --model", "not there yet; write the detections to a file and give it "
                                       "with --results");
  }
  reject_unknown_options(args);
  if (args.size() != 1) {
    throw InputError("DATASET", args.empty() ? "missing (see flexsight eval-det --help)"
                                             : "expected one data set, got " +
                                                   std::to_string(args.size()) + " arguments");
  }
  options.dataset = args.front();
  if (options.results.empty()) {
    throw InputError("option --results", "the detections file is required (see --help)");
  }
  if (options.out.empty()) throw InputError("option --out", "an output folder is required");
  return options;
}

// The detections to score, one list per image of `truth`. A results file for now; the
// detector run on each image (--model: flexsight detect's SsdDetector on
// truth.load_rgb(i)) will be a second branch here that fills the same lists.
DetectionResults collect_detections(const EvalDetOptions& options, const DetectionGroundTruth& truth) {
  return read_detection_results(options.results, truth);
}

std::string caption(const DetectionImage& image) {
  if (image.coco_id < 0) {
    return "scene " + std::to_string(image.scene_id) + ", im " + std::to_string(image.im_id);
  }
  std::string text = "image " + std::to_string(image.coco_id);
  if (image.scene_id >= 0 && image.im_id >= 0) {
    text += " (scene " + std::to_string(image.scene_id) + ", im " + std::to_string(image.im_id) + ")";
  }
  return text;
}

// The first `count` images with their boxes; reads their pictures, so a missing image
// file fails here, before anything is written.
std::vector<MontageImage> montage_images(const DetectionGroundTruth& truth,
                                         const DetectionResults& detections, int count) {
  std::vector<MontageImage> images;
  for (std::size_t i = 0; i < truth.images().size() && static_cast<int>(i) < count; ++i) {
    MontageImage image;
    image.rgb = truth.load_rgb(i);
    image.caption = caption(truth.images()[i]);
    image.truth = truth.images()[i].truth;
    image.detections = detections.per_image[i];
    images.push_back(std::move(image));
  }
  return images;
}

std::string fraction_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4f", value);
  return std::isfinite(value) ? text : "-";
}

}  // namespace

int run_eval_det_command(std::vector<std::string> args) {
  if (const auto code = usage_exit_code(args, print_help)) return *code;
  const EvalDetOptions options = parse_options(std::move(args));

  // Every input is read and checked before anything is written.
  const DetectionGroundTruth truth(options.dataset);
  std::vector<std::vector<TruthBox>> truth_boxes;
  bool any_truth = false;
  for (const DetectionImage& image : truth.images()) {
    truth_boxes.push_back(image.truth);
    for (const TruthBox& box : image.truth) any_truth = any_truth || !box.crowd;
  }
  if (!any_truth) {
    throw InputError(truth.source(), "has no ground-truth box (no visible object): nothing to score");
  }
  const DetectionResults detections = collect_detections(options, truth);
  DetectionEvalOptions eval_options;
  eval_options.iou_threshold = options.iou_threshold;
  DetectionReport report;
  report.dataset = truth.source();
  report.dataset_format = truth.format() == DetectionGroundTruth::Format::coco ? "COCO" : "BOP";
  report.detections = detections.source;
  report.detections_format = detections.format;
  report.scores = evaluate_detections(truth_boxes, detections.per_image, truth.categories(), eval_options);
  const cv::Mat curves = draw_pr_curves(report.scores);
  const cv::Mat montage = draw_detection_montage(montage_images(truth, detections, options.montage));

  // The folder appears whole or not at all.
  StagedFolder staged(options.out, options.overwrite, "--out");
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
  return 0;
}

}  // namespace flexsight
