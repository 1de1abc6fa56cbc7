#include "host/eval/pose_scoring.h"

#include <cmath>
#include <filesystem>
#include <optional>

#include "host/dataset/dataset_files.h"
#include "host/eval/pose_recall.h"
#include "host/io/input_error.h"
#include "host/io/progress_bar.h"
#include "host/pose/model_symmetries.h"
#include "host/synth/part_library.h"

namespace flexsight {
namespace {

// models_info's diameter and the mesh's may differ by rounding, not more.
constexpr double kDiameterTolerance = 0.01;

// The estimates by image; one for an image that is not scored is an error naming the
// results file.
std::map<std::pair<int, int>, std::vector<EstimateInstance>> estimates_by_image(const PoseScoringInput& input) {
  std::set<std::pair<int, int>> images;
  for (std::size_t i = 0; i < input.image_count; ++i) {
    images.insert({input.reader->ref(i).scene_id, input.reader->ref(i).im_id});
  }
  std::map<std::pair<int, int>, std::vector<EstimateInstance>> by_image;
  for (std::size_t i = 0; i < input.records.size(); ++i) {
    const PoseEstimateRecord& r = input.records[i];
    if (!images.count({r.scene_id, r.im_id})) {
      throw InputError(input.records_path, "estimate " + std::to_string(i + 1) + ": scene_id " +
                                               std::to_string(r.scene_id) + ", im_id " + std::to_string(r.im_id) +
                                               " is not an image of the data set");
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

}  // namespace

std::string default_models_info_beside(const std::string& cad_dir) {
  const std::string beside = (std::filesystem::path(cad_dir) / "models_info.json").string();
  return dataset_files::is_file(beside) ? beside : std::string(FLEXSIGHT_DEFAULT_MODELS_INFO);
}

PoseScoringModels load_pose_scoring_models(const std::set<int>& obj_ids, const std::string& cad_dir,
                                           const std::string& models_info,
                                           const std::map<int, std::string>& source_of) {
  const PartLibrary parts = PartLibrary::load_folder(cad_dir);
  const std::map<int, ModelInfo> infos = read_models_info(models_info);
  PoseScoringModels loaded;
  for (int obj_id : obj_ids) {
    const auto named = source_of.find(obj_id);
    const std::string source = named == source_of.end() ? cad_dir : named->second;
    const int index = parts.index_of(obj_id);
    if (index < 0) throw InputError(source, "obj_id " + std::to_string(obj_id) + " has no CAD model in " + cad_dir);
    const auto info = infos.find(obj_id);
    if (info == infos.end()) throw InputError(source, "obj_id " + std::to_string(obj_id) + " is not in " + models_info);
    const std::shared_ptr<const Mesh>& mesh = parts.part(index).mesh;
    const double mesh_diameter = mesh->diameter;
    if (std::abs(info->second.diameter - mesh_diameter) > kDiameterTolerance * mesh_diameter) {
      throw InputError(models_info,
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

void check_pose_estimates(const PoseScoringInput& input) { estimates_by_image(input); }

std::set<int> ground_truth_obj_ids(const BopReader& reader) {
  std::set<int> ids;
  for (std::size_t i = 0; i < reader.size(); ++i) {
    for (const PartAnnotation& part : reader.record(i).parts) ids.insert(part.obj_id);
  }
  return ids;
}

std::map<int, std::string> ground_truth_sources(const BopReader& reader) {
  std::map<int, std::string> sources;
  for (std::size_t i = 0; i < reader.size(); ++i) {
    for (const PartAnnotation& part : reader.record(i).parts) {
      sources.emplace(part.obj_id, (std::filesystem::path(reader.scene_dir(i)) / "scene_gt.json").string());
    }
  }
  return sources;
}

PoseReport score_pose_estimates(const PoseScoringInput& input, const PoseScoringModels& models) {
  const auto by_image = estimates_by_image(input);
  std::map<int, const PoseErrorModel*> model_views;
  for (const auto& [obj_id, model] : models.models) model_views[obj_id] = model.get();
  PoseEvalSettings settings;
  settings.min_visib_fract = input.min_visib;
  PoseRecallAccumulator accumulator(model_views, settings);
  PoseReport report;
  report.dataset = input.dataset;
  report.results = input.records_path;
  report.cad = input.cad;
  report.models_info = input.models_info;
  report.results_lines = static_cast<long>(input.records.size());
  report.settings = settings;
  report.symmetric = models.symmetric;

  std::optional<ProgressBar> progress;
  if (input.progress) progress.emplace(static_cast<std::int64_t>(input.image_count), "images scored");
  for (std::size_t i = 0; i < input.image_count; ++i) {
    const BopImageRecord& record = input.reader->record(i);
    if (progress) progress->advance();
    // One flip makes every ground-truth pose a reflection, which no estimate (a
    // rotation) can equal: such images are left out, and counted.
    if (mirrored(record)) {
      ++report.images_skipped_mirrored;
      continue;
    }
    const AnnotatedImage image = input.reader->load(i);
    PoseEvalImage scored;
    scored.K = image.camera.K;
    scored.width = image.rgb.cols;
    scored.height = image.rgb.rows;
    scored.depth = image.depth;
    for (const PartAnnotation& part : image.parts) {
      scored.truth.push_back({part.obj_id, Pose{part.cam_R_m2c, part.cam_t_m2c}, part.visib_fract});
    }
    const auto estimates = by_image.find({image.scene_id, image.im_id});
    if (estimates != by_image.end()) scored.estimates = estimates->second;
    accumulator.add_image(scored);
  }
  if (progress) progress->finish();
  report.images = accumulator.images();
  report.total = accumulator.total();
  report.per_object = accumulator.per_object();
  return report;
}

}  // namespace flexsight
