#pragma once
// Scores 6D pose estimates against a BOP data set's ground truth (BOP Challenge 2019+:
// ADD(-S), VSD, MSSD, MSPD, AR): the part shared by `flexsight eval-pose` and
// `flexsight pose DATASET --gt-boxes`, which scores what it has just estimated.
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "host/dataset/bop_pose_results.h"
#include "host/dataset/bop_reader.h"
#include "host/eval/pose_errors.h"
#include "host/eval/pose_report.h"

namespace flexsight {

// CAD_DIR/models_info.json when there is one, else the table the repository ships for
// the T-LESS meshes.
std::string default_models_info_beside(const std::string& cad_dir);

// The error models (mesh, diameter, symmetries) of the parts one evaluation needs.
struct PoseScoringModels {
  std::map<int, std::unique_ptr<PoseErrorModel>> models;
  std::map<int, bool> symmetric;
};

// Loads the meshes of `obj_ids` from `cad_dir` with their diameters and symmetries from
// `models_info`. InputError naming `source_of(obj_id)`'s file for an object without a
// mesh or without an entry, and naming models_info when its diameter does not fit the
// mesh (a table made for other meshes).
PoseScoringModels load_pose_scoring_models(const std::set<int>& obj_ids, const std::string& cad_dir,
                                           const std::string& models_info,
                                           const std::map<int, std::string>& source_of);

// The obj_ids of the data set's ground truth (all images).
std::set<int> ground_truth_obj_ids(const BopReader& reader);

// Each obj_id of the data set's ground truth with the scene_gt.json that first names it:
// the file an error about that object points the user to.
std::map<int, std::string> ground_truth_sources(const BopReader& reader);

struct PoseScoringInput {
  const BopReader* reader = nullptr;
  std::string dataset;          // the reader's folder, for the report
  std::size_t image_count = 0;  // the first image_count images are scored
  std::vector<PoseEstimateRecord> records;
  std::string records_path;     // named in errors: an estimate for an unknown image
  std::string cad, models_info;
  double min_visib = 0.1;
  bool progress = true;
};

// InputError naming records_path for an estimate of an image outside the scored ones:
// callers check this before they start writing.
void check_pose_estimates(const PoseScoringInput& input);

// The report (every field of PoseReport filled). Throws InputError for an estimate of an
// image outside the scored ones.
PoseReport score_pose_estimates(const PoseScoringInput& input, const PoseScoringModels& models);

}  // namespace flexsight
