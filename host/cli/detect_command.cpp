// flexsight detect: the part detector (host/detect/ssd_detector.h) on images; COCO results
// JSON, a picture of the boxes, or a table, and the time of each stage.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <set>

#include "host/cli/arguments.h"
#include "host/cli/backend.h"
#include "host/cli/commands.h"
#include "host/cli/detection_outputs.h"
#include "host/cli/image_inputs.h"
#include "host/cli/tile_option.h"
#include "host/detect/detection_drawing.h"
#include "host/detect/detector_model.h"
#include "host/detect/ssd_detector.h"
#include "host/detect/tiled_detection.h"
#include "host/io/image_io.h"
#include "host/io/input_error.h"
#include "host/io/output_path.h"
#include "host/io/progress_bar.h"

namespace flexsight {
namespace {

namespace fs = std::filesystem;

constexpr int kSheetImages = 16;

void print_help() {
  std::cout
      << "usage: flexsight detect IMAGE... [options]\n"
         "Finds the T-LESS parts in each IMAGE (files, or folders: their .png, .jpg and .jpeg\n"
         "files) with an SSD detector. The inputs are sorted by path; an image's image_id is\n"
         "its 1-based position in that sorted list.\n"
         "  --model M.onnx          the detector: M.onnx with anchors.csv, labels.txt and\n"
         "                          optionally model.json beside it (default:\n"
         "                          $FLEXSIGHT_DETECT_MODEL, else the shipped\n"
         "                          "
      << default_detector_model_path()
      << ")\n"
         "  -o DETS.json            detections in the COCO results format: a list of\n"
         "                          {image_id, category_id, bbox [x, y, width, height] in pixels,\n"
         "                          score, file_name}; without -o a table goes to stdout\n"
         "  --png BOXES.png         the image with its boxes; with several images a grid of the\n"
         "                          first 16\n"
         "  --score S               keep boxes scoring above S, in [0, 1] (default 0.3)\n"
         "  --iou I                 suppress a box overlapping a better one of its class by\n"
         "                          IoU > I, in [0, 1] (default 0.6)\n"
         "  --top-k K               candidates per class entering suppression, 1..1024\n"
         "                          (default 100)\n"
         "  --max-detections N      detections per image at most, 1..100000 (default 100)\n"
         "  --parts IDS             known-part mode: only these classes (object ids separated\n"
         "                          by commas, e.g. 5,12), scored by the softmax over them and\n"
         "                          the background (docs/detect.md)\n"
         "  --dnn-target cpu|opencl where OpenCV DNN runs the network (default cpu; opencl: on\n"
         "                          OpenCV's own OpenCL device, GPUs only unless\n"
         "                          OPENCV_DNN_OPENCL_ALLOW_ALL_DEVICES=1)\n"
      << tile_option_help(26)
      << "  --threads N             OpenCV's threads (network, resizing); 0 = all cores (default)\n"
         "  --quiet                 no progress line\n"
         "The post-processing (decoding, NMS) runs on --device:\n"
      << backend_options_help();
}

struct DetectOptions {
  std::string model;
  std::string output;
  std::string png;
  SsdDetectorOptions detector;
  int threads = 0;
  bool quiet = false;
  BackendOptions backend;
  int tile = 0;  // --tile: 0 = the whole image
};

// A threshold in [0, 1]; NaN is refused too.
float unit_interval(std::vector<std::string>& args, const std::string& option, float fallback) {
  const double value = take_number_option(args, option, fallback);
  if (!(value >= 0.0 && value <= 1.0)) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", value);
    throw InputError("option " + option, std::string("must lie in [0, 1], got ") + text);
  }
  return static_cast<float>(value);
}

int whole_option(std::vector<std::string>& args, const std::string& option, int fallback, int lo,
                 int hi) {
  const std::string text = take_option(args, option);
  return text.empty() ? fallback : static_cast<int>(parse_whole_number(option, text, lo, hi));
}

DetectOptions take_detect_options(std::vector<std::string>& args) {
  DetectOptions options;
  options.model = take_option(args, "--model");
  options.output = take_option(args, "-o");
  if (options.output.empty()) options.output = take_option(args, "--output");
  options.png = take_option(args, "--png");
  SsdDetectorOptions& d = options.detector;
  d.score_threshold = unit_interval(args, "--score", d.score_threshold);
  d.iou_threshold = unit_interval(args, "--iou", d.iou_threshold);
  d.top_k_per_class = whole_option(args, "--top-k", d.top_k_per_class, 1, 1024);
  d.max_detections = whole_option(args, "--max-detections", d.max_detections, 1, 100000);
  const std::string target = take_option(args, "--dnn-target");
  if (!target.empty()) d.dnn_target = parse_dnn_target(target);
  options.tile = take_tile_option(args);
  const bool parts_given = std::find(args.begin(), args.end(), "--parts") != args.end();
  const std::string parts = take_option(args, "--parts");
  if (parts_given) d.parts = parse_known_parts(parts);
  options.threads = whole_option(args, "--threads", 0, 0, 1024);
  options.quiet = take_flag(args, "--quiet");
  options.backend = take_backend_options(args);
  reject_unknown_options(args);
  return options;
}

// Every output's folder exists and no two outputs share a path, checked before the model
// loads, so that a mistyped path fails in a second.
void check_outputs(const DetectOptions& options, const std::vector<std::string>& images) {
  for (const std::string& path : {options.output, options.png}) {
    if (path.empty()) continue;
    check_output_file(path);
    for (const std::string& image : images) {
      std::error_code ec;
      if (fs::equivalent(path, image, ec)) {
        throw InputError(path, "is an input image; it would be overwritten");
      }
    }
  }
  if (!options.output.empty() && options.output == options.png) {
    throw InputError("option --png", "names the same file as -o");
  }
  if (!options.png.empty() && !cv::haveImageWriter(options.png)) {
    throw InputError(options.png,
                     "cannot be written: OpenCV has no encoder for its extension "
                     "(use .png or .jpg)");
  }
}

double median_ms(std::vector<double> seconds) {
  if (seconds.empty()) return 0.0;
  const size_t middle = seconds.size() / 2;
  std::nth_element(seconds.begin(), seconds.begin() + middle, seconds.end());
  double value = seconds[middle];
  if (seconds.size() % 2 == 0) {
    value = (value + *std::max_element(seconds.begin(), seconds.begin() + middle)) / 2.0;
  }
  return value * 1e3;
}

struct StageTimes {
  std::vector<double> read, preprocess, forward, postprocess;
};

void print_timing(const StageTimes& times, size_t images, double wall_seconds) {
  std::fprintf(stderr,
               "time per image (median of %zu): read %.1f ms, preprocess %.1f ms, forward "
               "%.1f ms, post-process %.2f ms; %.1f images/s end to end (reading included)\n",
               images, median_ms(times.read), median_ms(times.preprocess), median_ms(times.forward),
               median_ms(times.postprocess), wall_seconds > 0.0 ? images / wall_seconds : 0.0);
}

// The detections of one image, whole or in tiles; a tiled image's stage times add up over
// its tiles.
std::vector<ObjectDetection> detect_timed(SsdDetector& detector, const cv::Mat& bgr, const TilingPlan& tiling,
                                          float iou, DetectionTimes& spent) {
  const auto detect = [&](const cv::Mat& part) {
    DetectionTimes tile_spent;
    std::vector<ObjectDetection> found = detector.detect(part, &tile_spent);
    spent.preprocess += tile_spent.preprocess;
    spent.forward += tile_spent.forward;
    spent.postprocess += tile_spent.postprocess;
    return found;
  };
  return detect_in_tiles(detect, bgr, tiling, iou);
}

}  // namespace

int run_detect_command(std::vector<std::string> args) {
  if (const std::optional<int> code = usage_exit_code(args, print_help)) return *code;
  DetectOptions options = take_detect_options(args);
  if (args.empty()) throw InputError("detect", "no IMAGE given");

  // Everything that can be checked is, before any image is processed or output written.
  const std::vector<std::string> files = list_input_images(args);
  check_outputs(options, files);
  if (options.tile > 0) {
    for (const std::string& file : files) check_tile_fits(options.tile, load_rgb8(file).size(), file);
  }
  const std::string model = resolve_detector_model_path(options.model);
  if (options.threads > 0) cv::setNumThreads(options.threads);
  ComputeBackend backend(options.backend);
  SsdDetector detector(model, backend, options.detector);
  std::cerr << "detect: " << files.size() << " image" << (files.size() == 1 ? "" : "s") << " with "
            << model << "; " << detector.planned() << "\n";
  const TilingPlan tiling = fixed_tiling(options.tile);
  if (tiling.tile > 0) {
    std::cerr << "detect: tiles of " << tiling.tile << " px, stride " << tiling.stride << " px\n";
  }

  std::vector<ImageDetections> results;
  std::vector<cv::Mat> sheet_images;  // RGB, the first kSheetImages, for --png
  StageTimes times;
  std::optional<ProgressBar> progress;
  if (files.size() > 1 && !options.quiet) progress.emplace(files.size(), "images");
  const auto start = std::chrono::steady_clock::now();
  for (size_t i = 0; i < files.size(); ++i) {
    const auto read_start = std::chrono::steady_clock::now();
    const cv::Mat rgb = load_rgb8(files[i]);
    cv::Mat bgr;
    cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
    times.read.push_back(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - read_start).count());
    DetectionTimes spent;
    ImageDetections image;
    image.file = files[i];
    image.image_id = static_cast<int>(i) + 1;
    image.width = rgb.cols;
    image.height = rgb.rows;
    image.found = detect_timed(detector, bgr, tiling, options.detector.iou_threshold, spent);
    times.preprocess.push_back(spent.preprocess);
    times.forward.push_back(spent.forward);
    times.postprocess.push_back(spent.postprocess);
    if (!options.png.empty() && sheet_images.size() < kSheetImages) sheet_images.push_back(rgb);
    results.push_back(std::move(image));
    if (progress) progress->advance();
  }
  const double wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (progress) progress->finish();

  // Outputs only now, each written under a temporary name and renamed.
  size_t detections = 0;
  for (const ImageDetections& image : results) detections += image.found.size();
  if (!options.png.empty()) {
    std::vector<std::vector<ObjectDetection>> found;
    for (size_t i = 0; i < sheet_images.size(); ++i) found.push_back(results[i].found);
    write_image(options.png, sheet_images.size() == 1
                                 ? draw_detections(sheet_images[0], found[0])
                                 : detection_contact_sheet(sheet_images, found));
  }
  if (!options.output.empty()) {
    write_coco_results(options.output, results);
    std::cerr << "wrote " << detections << " detection" << (detections == 1 ? "" : "s") << " of "
              << results.size() << " image" << (results.size() == 1 ? "" : "s") << " to "
              << options.output << "\n";
  } else {
    std::cout << detection_table(results, detector.labels());
  }
  print_timing(times, results.size(), wall_seconds);
  return 0;
}

}  // namespace flexsight
