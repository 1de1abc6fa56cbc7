#include "host/eval/pick_evaluation.h"

#include <filesystem>
#include <iostream>
#include <map>

#include "host/dataset/bop_reader.h"
#include "host/io/calibration.h"
#include "host/io/image_io.h"
#include "host/io/input_error.h"
#include "host/io/pfm.h"
#include "host/stereo/pipeline_rules.h"

namespace flexsight {

PickReport pick_report_header(const std::string& bins_dir, const PickSettings& settings, const PickSession& session) {
  PickReport report;
  report.bins_dir = bins_dir;
  report.model = settings.model;
  report.templates = settings.templates;
  report.cad = settings.cad;
  for (const DetectorLabel& label : session.detector().labels()) {
    report.categories.push_back({label.category_id, label.name});
  }
  return report;
}

PoseScoringModels load_pick_scoring_models(std::map<int, std::string> truth_sources,
                                           const PickSettings& settings, const PickSession& session,
                                           const std::string& models_info) {
  std::map<int, std::string>& source_of = truth_sources;
  std::set<int> obj_ids;
  for (const auto& entry : source_of) obj_ids.insert(entry.first);
  for (const DetectorLabel& label : session.detector().labels()) {
    if (!source_of.count(label.category_id)) source_of[label.category_id] = settings.model;
    obj_ids.insert(label.category_id);
  }
  return load_pose_scoring_models(obj_ids, settings.cad, models_info, source_of);
}

void check_bin_inputs(const BinFiles& files, const StereoParams& stereo, bool passive_stereo) {
  const StereoPair pair = load_stereo_pair(files.left, files.right);
  read_stereo_camera(files.calib).resized_to(pair.left.cols, pair.left.rows);
  validate_inputs(pair.left, pair.right, stereo);
  const auto same_size = [&](const std::string& path, const cv::Size& size) {
    if (size != pair.left.size()) {
      throw InputError(path, "is " + std::to_string(size.width) + "x" + std::to_string(size.height) + ", the bin's " +
                                 files.left + " " + std::to_string(pair.left.cols) + "x" +
                                 std::to_string(pair.left.rows));
    }
  };
  if (passive_stereo) {
    const StereoPair passive = load_stereo_pair(files.left_passive, files.right_passive);
    same_size(files.left_passive, passive.left.size());
  } else if (!files.left_passive.empty()) {
    same_size(files.left_passive, load_rgb8(files.left_passive).size());
  }
  const BopReader reader(files.dir);
  if (reader.size() != 1) {
    throw InputError(files.dir, "is not a synth-bin folder: it holds " + std::to_string(reader.size()) + " images, not 1");
  }
  const std::string truth_path = (std::filesystem::path(files.dir) / "disp0GT.pfm").string();
  same_size(truth_path, read_pfm(truth_path).size());
  const std::string mask_path = (std::filesystem::path(files.dir) / "mask0nocc.png").string();
  same_size(mask_path, load_rgb8(mask_path).size());
}

BinPickRun pick_and_score_bin(PickSession& session, const BinFiles& files, const StereoParams& stereo,
                              bool passive_stereo, const PoseScoringModels& models, const PickSettings& settings,
                              const std::string& models_info) {
  const StereoPair pair = load_stereo_pair(files.left, files.right);
  const StereoCamera rig = read_stereo_camera(files.calib).resized_to(pair.left.cols, pair.left.rows);
  session.set_ndisp(stereo.ndisp);
  validate_inputs(pair.left, pair.right, stereo);
  const cv::Mat texture = files.left_passive.empty() ? cv::Mat() : load_rgb8(files.left_passive);
  BinPickRun run;
  run.result = session.pick(pair.left, pair.right, rig, texture);
  cv::Mat no_pattern;
  if (passive_stereo) {
    if (!settings.quiet) std::cerr << "  stereo without the pattern\n";
    const StereoPair passive_pair = load_stereo_pair(files.left_passive, files.right_passive);
    no_pattern = session.disparity(passive_pair.left, passive_pair.right);
  }
  run.score = score_pick_on_bin(files.dir, run.result, no_pattern, models, settings.cad, models_info);
  run.left_view = texture.empty() ? pair.left : texture;
  return run;
}

}  // namespace flexsight
