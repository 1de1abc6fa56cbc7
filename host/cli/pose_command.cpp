// flexsight pose: the 6D pose of parts in boxes (host/pose/pose_estimator.h). Two
// forms: one image with its depth and boxes, or every ground-truth box of a BOP data
// set with its depth, scored at once (the benchmark of docs/pose.md).
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <set>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "host/cli/arguments.h"
#include "host/cli/commands.h"
#include "host/cli/pose_image_form.h"
#include "host/cli/pose_outputs.h"
#include "host/dataset/bop_pose_results.h"
#include "host/dataset/bop_reader.h"
#include "host/eval/pose_scoring.h"
#include "host/io/input_error.h"
#include "host/io/staged_folder.h"
#include "host/pose/dataset_posing.h"
#include "host/dataset/detection_data.h"
#include "host/pose/edge_thresholds.h"
#include "host/pose/pose_models.h"

namespace flexsight {
namespace {

namespace fs = std::filesystem;

void print_help() {
  std::cout
      << "usage: flexsight pose DATASET --gt-boxes --templates T --out DIR [options]\n"
         "       flexsight pose IMAGE --depth DEPTH.pfm --calib CALIB --boxes DETS.json\n"
         "                          --templates T -o POSES.json [--csv POSES.csv] [--png P.png]\n"
         "  IMAGE              an image (PNG, JPEG); --depth DEPTH.pfm in mm, or --disparity\n"
         "                     D.pfm with --calib (Middlebury, KITTI or OpenCV stereo\n"
         "                     calibration, which also gives the camera); --boxes: COCO\n"
         "                     detections (flexsight detect -o), category_id = object id,\n"
         "                     those scoring at least --score (default 0.3) are posed\n"
         "  DATASET            a BOP scene or split folder with depth/: every ground-truth\n"
         "                     box (bbox_visib) is posed, and the result scored\n"
         "  --gt-boxes         pose the data set's ground-truth boxes (the only boxes a data\n"
         "                     set form takes for now)\n"
         "  --templates T      edge templates (flexsight pose-templates CAD_DIR -o T)\n"
         "  --cad DIR          the CAD models the templates were made from (default: the\n"
         "                     T-LESS folder of the detection data)\n"
         "  --out DIR          data set form: poses.csv (BOP results), report.md,\n"
         "                     report.json, poses.jpg (outlines at the estimated poses)\n"
         "  --min-visib F      data set form: pose parts at least this visible (default 0.1,\n"
         "                     BOP's); the same parts are the scoring's targets\n"
         "  --models-info FILE data set form: diameters and symmetries for the scoring\n"
         "                     (default: DIR_OF_CAD/models_info.json when present, else the\n"
         "                     repository's T-LESS table)\n"
         "  --limit N          data set form: the first N images only (posed and scored)\n"
         "  --refinement R     depth (default: ICP from the template's pose), edges (D2CO\n"
         "                     alone: search + LM on edges) or both (LM, then ICP)\n"
         "  --edges E          how the edge thresholds meet the image: fixed (grey\n"
         "                     levels as they are), contrast (the box's grey levels\n"
         "                     stretched first), noise (kept above the box's\n"
         "                     gradient noise) or contrast+noise (default fixed;\n"
         "                     docs/pose.md)\n"
         "  --threads N        images posed at once (default: all cores)\n"
         "  --overwrite        replace DIR when it is not empty\n";
}

PoseRefinement parse_refinement(const std::string& text) {
  if (text.empty() || text == "depth") return PoseRefinement::kDepthOnly;
  if (text == "both") return PoseRefinement::kBoth;
  if (text == "edges") return PoseRefinement::kEdgesOnly;
  throw InputError("option --refinement", "expected both, edges or depth, got '" + text + "'");
}

DcdParams::EdgeThresholds parse_edges(const std::string& text, DcdParams::EdgeThresholds default_value) {
  return text.empty() ? default_value : edge_thresholds_named(text, "--edges");
}

int run_dataset_form(const std::string& dataset, std::vector<std::string>& args) {
  if (!take_flag(args, "--gt-boxes")) {
    throw InputError("pose " + dataset, "a data set form needs --gt-boxes (pose its ground-truth boxes)");
  }
  const std::string templates = take_option(args, "--templates");
  std::string cad = take_option(args, "--cad");
  const std::string out = take_option(args, "--out");
  const double min_visib = take_number_option(args, "--min-visib", 0.1);
  const std::string limit_text = take_option(args, "--limit");
  const std::string threads_text = take_option(args, "--threads");
  std::string models_info = take_option(args, "--models-info");
  PoseEstimatorParams params;
  params.refinement = parse_refinement(take_option(args, "--refinement"));
  params.dcd.thresholds = parse_edges(take_option(args, "--edges"), params.dcd.thresholds);
  const bool overwrite = take_flag(args, "--overwrite");
  reject_unknown_options(args);
  if (templates.empty()) throw InputError("option --templates", "missing (make them with flexsight pose-templates CAD_DIR -o FILE)");
  if (out.empty()) throw InputError("option --out", "missing: the folder to write the poses and report to");
  if (!(min_visib >= 0.0 && min_visib <= 1.0)) throw InputError("option --min-visib", "must be in [0, 1]");
  const std::int64_t limit = limit_text.empty() ? -1 : parse_whole_number("--limit", limit_text, 1, 1000000000);
  const int threads = threads_text.empty() ? omp_get_max_threads()
                                           : static_cast<int>(parse_whole_number("--threads", threads_text, 1, 1024));
  if (cad.empty()) cad = default_cad_dir();
  if (models_info.empty()) models_info = default_models_info_beside(cad);

  const BopReader reader(dataset);
  const std::size_t image_count = limit < 0 ? reader.size() : std::min<std::size_t>(reader.size(), limit);
  for (std::size_t i = 0; i < image_count; ++i) reader.check_boxes_inside_image(i, true);
  StagedFolder staged(out, overwrite, "--out");
  const PoseModels models(templates, cad);
  const std::size_t boxes = count_boxes_to_pose(reader, image_count, models, min_visib);
  if (boxes == 0) throw InputError(dataset, "has no ground-truth box at least " + std::to_string(min_visib) + " visible");
  // The scoring's inputs (every ground-truth part's mesh and models_info entry) are
  // checked before any part is posed.
  std::set<int> truth_ids;
  for (std::size_t i = 0; i < image_count; ++i) {
    for (const PartAnnotation& part : reader.record(i).parts) truth_ids.insert(part.obj_id);
  }
  const PoseScoringModels scoring_models = load_pose_scoring_models(truth_ids, cad, models_info, ground_truth_sources(reader));

  const DatasetPoses poses = pose_ground_truth_boxes(reader, image_count, boxes, models, params, min_visib, threads);
  const std::vector<PoseEstimateRecord>& records = poses.records;
  PoseScoringInput scoring;
  scoring.reader = &reader;
  scoring.dataset = dataset;
  scoring.image_count = image_count;
  scoring.records = records;
  scoring.records_path = out + "/poses.csv";
  scoring.cad = cad;
  scoring.models_info = models_info;
  scoring.min_visib = min_visib;
  const PoseReport report = score_pose_estimates(scoring, scoring_models);
  write_pose_dataset_outputs(staged.path(), reader, image_count, records, poses.timing, report, models);
  staged.commit();
  std::cout << std::fixed << std::setprecision(3) << "pose: " << records.size() << " parts in " << image_count << " images: ADD(-S) recall "
            << report.total.add_recall() << ", AR " << report.total.ar() << " -> " << out << "\n";
  return 0;
}

}  // namespace

int run_pose_command(std::vector<std::string> args) {
  if (auto code = usage_exit_code(args, print_help)) return *code;
  if (args.empty() || args[0].rfind("-", 0) == 0) throw InputError("pose", "expected a data set folder or an image first");
  const std::string input = args[0];
  args.erase(args.begin());
  if (fs::is_directory(input)) return run_dataset_form(input, args);
  std::string cad = take_option(args, "--cad");
  PoseEstimatorParams params;
  params.refinement = parse_refinement(take_option(args, "--refinement"));
  params.dcd.thresholds = parse_edges(take_option(args, "--edges"), params.dcd.thresholds);
  return run_pose_image_form(input, args, cad.empty() ? default_cad_dir() : cad, params);
}

}  // namespace flexsight
