// flexsight eval-pose: scores 6D pose estimates (a BOP results CSV) against the ground
// truth of a BOP data set as the BOP Challenge 2019+ does (ADD(-S) recall, AR_VSD,
// AR_MSSD, AR_MSPD, AR) and writes report.json and report.md.
#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "host/cli/arguments.h"
#include "host/cli/commands.h"
#include "host/cli/synth_settings_options.h"
#include "host/dataset/bop_pose_results.h"
#include "host/dataset/bop_reader.h"
#include "host/dataset/dataset_files.h"
#include "host/dataset/detection_data.h"
#include "host/eval/pose_report.h"
#include "host/eval/pose_scoring.h"
#include "host/io/input_error.h"
#include "host/io/report_text.h"
#include "host/io/staged_folder.h"

namespace flexsight {

namespace {

namespace fs = std::filesystem;

// A models_info.json whose diameter differs from the mesh's by more than this describes
// other meshes (scaled ones, say): its thresholds and symmetry offsets would be wrong.
struct EvalPoseOptions {
  std::string dataset;
  std::string results;
  std::string out;
  std::string cad;
  std::string models_info;
  double min_visib = 0.1;
  bool overwrite = false;
  bool quiet = false;
};

// DIR_OF_CAD/models_info.json when there is one, else the repository's table for the
// T-LESS parts (models/tless-cad/models_info.json).

void print_help() {
  std::cout
      << "usage: flexsight eval-pose DATASET --results POSES.csv --out DIR [options]\n"
         "  DATASET               a BOP scene or split folder (scene_gt.json, scene_gt_info.json,\n"
         "                        scene_camera.json; depth/ for VSD)\n"
         "  --results POSES.csv   the estimates: BOP's results CSV\n"
         "                        (scene_id,im_id,obj_id,score,R,t,time; R row-major, t in mm)\n"
         "  --out DIR             output folder (new or empty): report.json, report.md\n"
         "  --overwrite           replace DIR when it is not empty\n"
         "  --cad DIR             the parts' meshes, ids from the file names (default\n"
         "                        " << default_cad_dir() << ")\n"
         "  --models-info FILE    diameters and symmetries in BOP's models_info.json format\n"
         "                        (default: DIR_OF_CAD/models_info.json when present, else\n"
         "                        " << FLEXSIGHT_DEFAULT_MODELS_INFO << ")\n"
         "  --min-visib F         least visible fraction of a target (default 0.1, BOP's)\n"
         "  --quiet               no progress line\n"
         "Metrics and conventions: docs/pose-eval.md.\n";
}

EvalPoseOptions parse_options(std::vector<std::string> args) {
  EvalPoseOptions options;
  options.results = take_option(args, "--results");
  options.out = take_option(args, "--out");
  options.overwrite = take_flag(args, "--overwrite");
  options.cad = take_option(args, "--cad");
  options.models_info = take_option(args, "--models-info");
  const std::string min_visib = take_option(args, "--min-visib");
  if (!min_visib.empty()) {
    try {
      std::size_t used = 0;
      options.min_visib = std::stod(min_visib, &used);
      if (used != min_visib.size()) options.min_visib = -1;
    } catch (const std::exception&) {
      options.min_visib = -1;
    }
    if (!(options.min_visib >= 0 && options.min_visib <= 1)) {
      throw InputError("option --min-visib", "expected a fraction in [0, 1], got '" + min_visib + "'");
    }
  }
  options.quiet = take_flag(args, "--quiet");
  reject_unknown_options(args);
  if (args.size() != 1) {
    throw InputError("DATASET", args.empty() ? "missing (see flexsight eval-pose --help)"
                                             : "expected one data set, got " + std::to_string(args.size()) +
                                                   " arguments");
  }
  options.dataset = args.front();
  if (options.results.empty()) throw InputError("option --results", "a BOP results CSV is required");
  if (options.out.empty()) throw InputError("option --out", "an output folder is required");
  if (options.cad.empty()) options.cad = default_cad_dir();
  if (options.models_info.empty()) options.models_info = default_models_info_beside(options.cad);
  return options;
}

// The parts the evaluation needs: the CAD mesh and models_info entry of every obj_id
// that the data set's ground truth or the results name, checked against each other.
}  // namespace

int run_eval_pose_command(std::vector<std::string> args) {
  if (const auto code = usage_exit_code(args, print_help)) return *code;
  const EvalPoseOptions options = parse_options(std::move(args));

  // Every input is read and checked before any image is: the data set's JSON files,
  // the results, the meshes and models_info of every obj_id, the output folder.
  const BopReader reader(options.dataset);
  if (reader.size() == 0) throw InputError(options.dataset, "has no image");
  PoseScoringInput input;
  input.reader = &reader;
  input.dataset = options.dataset;
  input.image_count = reader.size();
  input.records = read_bop_pose_results(options.results);
  input.records_path = options.results;
  input.cad = options.cad;
  input.models_info = options.models_info;
  input.min_visib = options.min_visib;
  input.progress = !options.quiet;
  check_pose_estimates(input);
  std::set<int> obj_ids = ground_truth_obj_ids(reader);
  std::map<int, std::string> source_of = ground_truth_sources(reader);
  for (const PoseEstimateRecord& r : input.records) {
    obj_ids.insert(r.obj_id);
    source_of[r.obj_id] = options.results;
  }
  const PoseScoringModels models = load_pose_scoring_models(obj_ids, options.cad, options.models_info, source_of);
  StagedFolder staged(options.out, options.overwrite, "--out");
  const PoseReport report = score_pose_estimates(input, models);

  const fs::path dir(staged.path());
  dataset_files::write_text((dir / "report.json").string(), to_json(report));
  dataset_files::write_text((dir / "report.md").string(), to_markdown(report));
  staged.commit();

  const PoseScores& s = report.total;
  std::cout << "eval-pose: " << report.images << " images, " << s.targets << " targets, " << input.records.size()
            << " estimates: ADD(-S) recall " << fraction_text(s.add_recall()) << ", AR "
            << fraction_text(s.ar()) << " (VSD " << (s.has_vsd ? fraction_text(s.ar_vsd()) : "-") << ", MSSD "
            << fraction_text(s.ar_mssd()) << ", MSPD " << fraction_text(s.ar_mspd()) << ") -> "
            << staged.target() << "\n";
  return 0;
}

}  // namespace flexsight
