// flexsight eval-pose: scores 6D pose estimates (a BOP results CSV) against the ground
// truth of a BOP data set as the BOP Challenge 2019+ does (ADD(-S) recall, AR_VSD,
// AR_MSSD, AR_MSPD, AR) and writes report.json and report.md.
#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "host/cli/arguments.h"
#include "host/cli/commands.h"
#include "host/cli/progress_bar.h"
#include "host/cli/synth_settings_options.h"
#include "host/dataset/bop_pose_results.h"
#include "host/dataset/bop_reader.h"
#include "host/dataset/dataset_files.h"
#include "host/eval/pose_recall.h"
#include "host/eval/pose_report.h"
#include "host/io/input_error.h"
#include "host/io/staged_folder.h"
#include "host/pose/model_symmetries.h"
#include "host/synth/part_library.h"

namespace flexsight {

namespace {

namespace fs = std::filesystem;

// A models_info.json whose diameter differs from the mesh's by more than this describes
// other meshes (scaled ones, say): its thresholds and symmetry offsets would be wrong.
constexpr double kDiameterTolerance = 0.01;

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

std::string default_cad_dir() { return detection_data_dir() + "/cad/tless"; }

// DIR_OF_CAD/models_info.json when there is one, else the repository's table for the
// T-LESS parts (models/tless-cad/models_info.json).
std::string default_models_info(const std::string& cad) {
  const std::string beside = (fs::path(cad) / "models_info.json").string();
  return dataset_files::is_file(beside) ? beside : std::string(FLEXSIGHT_DEFAULT_MODELS_INFO);
}

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
  if (options.models_info.empty()) options.models_info = default_models_info(options.cad);
  return options;
}

// The parts the evaluation needs: the CAD mesh and models_info entry of every obj_id
// that the data set's ground truth or the results name, checked against each other.
struct EvalModels {
  std::map<int, std::unique_ptr<PoseErrorModel>> models;
  std::map<int, bool> symmetric;
};

EvalModels load_models(const EvalPoseOptions& options, const std::set<int>& truth_ids,
                       const std::set<int>& result_ids) {
  const PartLibrary parts = PartLibrary::load_folder(options.cad);
  const std::map<int, ModelInfo> infos = read_models_info(options.models_info);
  std::set<int> needed = truth_ids;
  needed.insert(result_ids.begin(), result_ids.end());
  EvalModels loaded;
  for (int obj_id : needed) {
    const std::string source = result_ids.count(obj_id) ? options.results : options.dataset;
    const int index = parts.index_of(obj_id);
    if (index < 0) {
      throw InputError(source, "obj_id " + std::to_string(obj_id) + " has no CAD model in " + options.cad);
    }
    const auto info = infos.find(obj_id);
    if (info == infos.end()) {
      throw InputError(source, "obj_id " + std::to_string(obj_id) + " is not in " + options.models_info);
    }
    const std::shared_ptr<const Mesh>& mesh = parts.part(index).mesh;
    const double mesh_diameter = mesh->diameter;
    if (std::abs(info->second.diameter - mesh_diameter) > kDiameterTolerance * mesh_diameter) {
      throw InputError(options.models_info,
                       "obj " + std::to_string(obj_id) + ": diameter " + std::to_string(info->second.diameter) +
                           " mm, but " + parts.part(index).name + " measures " + std::to_string(mesh_diameter) +
                           " mm: a table for other meshes (pass the matching --models-info)");
    }
    loaded.models[obj_id] = std::make_unique<PoseErrorModel>(
        mesh, info->second.diameter, symmetry_transformations(info->second), info->second.symmetric());
    loaded.symmetric[obj_id] = info->second.symmetric();
  }
  return loaded;
}

// The results by image of the data set; an estimate for an image the data set lacks is
// an error naming the results file.
std::map<std::pair<int, int>, std::vector<EstimateInstance>> estimates_by_image(
    const std::vector<PoseEstimateRecord>& records, const BopReader& reader, const std::string& path) {
  std::set<std::pair<int, int>> images;
  for (std::size_t i = 0; i < reader.size(); ++i) images.insert({reader.ref(i).scene_id, reader.ref(i).im_id});
  std::map<std::pair<int, int>, std::vector<EstimateInstance>> by_image;
  for (std::size_t i = 0; i < records.size(); ++i) {
    const PoseEstimateRecord& r = records[i];
    if (!images.count({r.scene_id, r.im_id})) {
      throw InputError(path, "estimate " + std::to_string(i + 1) + ": scene_id " + std::to_string(r.scene_id) +
                                 ", im_id " + std::to_string(r.im_id) + " is not an image of the data set");
    }
    EstimateInstance estimate;
    estimate.obj_id = r.obj_id;
    estimate.pose.R = r.R;
    estimate.pose.t = r.t;
    estimate.score = r.score;
    by_image[{r.scene_id, r.im_id}].push_back(estimate);
  }
  return by_image;
}

bool mirrored(const BopImageRecord& record) {
  const bool h = record.camera.extra.is_object() && record.camera.extra.value("flip_horizontal", false);
  const bool v = record.camera.extra.is_object() && record.camera.extra.value("flip_vertical", false);
  return h != v;
}

std::string fraction_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4f", value);
  return std::isfinite(value) ? text : "-";
}

}  // namespace

int run_eval_pose_command(std::vector<std::string> args) {
  if (const auto code = usage_exit_code(args, print_help)) return *code;
  const EvalPoseOptions options = parse_options(std::move(args));

  // Every input is read and checked before any image is: the data set's JSON files,
  // the results, the meshes and models_info of every obj_id, the output folder.
  const BopReader reader(options.dataset);
  if (reader.size() == 0) throw InputError(options.dataset, "has no image");
  const std::vector<PoseEstimateRecord> records = read_bop_pose_results(options.results);
  std::set<int> truth_ids, result_ids;
  for (std::size_t i = 0; i < reader.size(); ++i) {
    for (const PartAnnotation& part : reader.record(i).parts) truth_ids.insert(part.obj_id);
  }
  for (const PoseEstimateRecord& r : records) result_ids.insert(r.obj_id);
  const auto by_image = estimates_by_image(records, reader, options.results);
  const EvalModels models = load_models(options, truth_ids, result_ids);
  StagedFolder staged(options.out, options.overwrite, "--out");

  std::map<int, const PoseErrorModel*> model_views;
  for (const auto& [obj_id, model] : models.models) model_views[obj_id] = model.get();
  PoseEvalSettings settings;
  settings.min_visib_fract = options.min_visib;
  PoseRecallAccumulator accumulator(model_views, settings);
  PoseReport report;
  report.dataset = options.dataset;
  report.results = options.results;
  report.cad = options.cad;
  report.models_info = options.models_info;
  report.results_lines = static_cast<long>(records.size());
  report.settings = settings;
  report.symmetric = models.symmetric;

  std::optional<ProgressBar> progress;
  if (!options.quiet) progress.emplace(static_cast<std::int64_t>(reader.size()), "images");
  for (std::size_t i = 0; i < reader.size(); ++i) {
    const BopImageRecord& record = reader.record(i);
    if (progress) progress->advance();
    // One flip makes every ground-truth pose a reflection, which no estimate (a
    // rotation) can equal: such images are left out, and counted.
    if (mirrored(record)) {
      ++report.images_skipped_mirrored;
      continue;
    }
    const AnnotatedImage image = reader.load(i);
    PoseEvalImage input;
    input.K = image.camera.K;
    input.width = image.rgb.cols;
    input.height = image.rgb.rows;
    input.depth = image.depth;
    for (const PartAnnotation& part : image.parts) {
      input.truth.push_back({part.obj_id, Pose{part.cam_R_m2c, part.cam_t_m2c}, part.visib_fract});
    }
    const auto estimates = by_image.find({image.scene_id, image.im_id});
    if (estimates != by_image.end()) input.estimates = estimates->second;
    accumulator.add_image(input);
  }
  if (progress) progress->finish();
  report.images = accumulator.images();
  report.total = accumulator.total();
  report.per_object = accumulator.per_object();

  const fs::path dir(staged.path());
  dataset_files::write_text((dir / "report.json").string(), to_json(report));
  dataset_files::write_text((dir / "report.md").string(), to_markdown(report));
  staged.commit();

  const PoseScores& s = report.total;
  std::cout << "eval-pose: " << report.images << " images, " << s.targets << " targets, " << records.size()
            << " estimates: ADD(-S) recall " << fraction_text(s.add_recall()) << ", AR "
            << fraction_text(s.ar()) << " (VSD " << (s.has_vsd ? fraction_text(s.ar_vsd()) : "-") << ", MSSD "
            << fraction_text(s.ar_mssd()) << ", MSPD " << fraction_text(s.ar_mspd()) << ") -> "
            << staged.target() << "\n";
  return 0;
}

}  // namespace flexsight
