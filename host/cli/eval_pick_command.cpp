// flexsight eval-pick: `pick` on every bin of a `synth bin` folder, scored against the
// bins' ground truth (host/cli/pick_scoring.h, pick_report.h; docs/pick.md).
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <opencv2/imgproc.hpp>

#include "host/cli/arguments.h"
#include "host/cli/commands.h"
#include "host/cli/pick_options.h"
#include "host/cli/pick_outputs.h"
#include "host/cli/pick_report.h"
#include "host/dataset/dataset_files.h"
#include "host/io/calibration.h"
#include "host/io/image_io.h"
#include "host/io/input_error.h"
#include "host/io/staged_folder.h"
#include "host/stereo/pipeline_rules.h"

namespace flexsight {
namespace {

namespace fs = std::filesystem;

// "12.3 s": the progress line's time, to a tenth of a second.
std::string seconds_text(double seconds) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f s", seconds);
  return text;
}

void print_help() {
  std::cout << "usage: flexsight eval-pick BINS_DIR --out DIR --templates T [options]\n"
               "Runs pick on every bin of BINS_DIR (a flexsight synth bin folder: one scene folder\n"
               "per bin with im0.png, im1.png, their passive twins, calib.txt, disp0GT.pfm,\n"
               "mask0nocc.png and the BOP ground truth) and scores it: DIR/report.json and\n"
               "DIR/report.md (pose recall, top-ranked part, detection mAP, stereo bad-2 with and\n"
               "without the pattern, seconds per stage), DIR/BIN.json and DIR/BIN.png per bin.\n"
               "  --out DIR          the report folder (must not exist, or be empty, unless\n"
               "                     --overwrite)\n"
               "  --overwrite        replace DIR\n"
               "  --pattern-only     leave out the matcher on the pair without the pattern\n"
               "                     (detection still looks at im0_passive.png when it is there)\n"
               "  --limit N          the first N bins only\n"
               "  --models-info F    the parts' diameters and symmetries (default: CAD_DIR's\n"
               "                     models_info.json, else the shipped T-LESS table)\n"
            << pick_options_help();
}

struct BinFiles {
  std::string dir, left, right, left_passive, right_passive, calib;
};

BinFiles bin_files(const fs::path& dir, bool passive_stereo) {
  BinFiles files{dir.string(), (dir / "im0.png").string(), (dir / "im1.png").string(),
                 (dir / "im0_passive.png").string(), (dir / "im1_passive.png").string(),
                 (dir / "calib.txt").string()};
  std::vector<std::string> required = {files.left, files.right, files.calib, (dir / "disp0GT.pfm").string(),
                                       (dir / "mask0nocc.png").string(), (dir / "scene_gt.json").string(),
                                       (dir / "scene_gt_info.json").string()};
  if (passive_stereo) {
    required.push_back(files.left_passive);
    required.push_back(files.right_passive);
  }
  for (const std::string& file : required) {
    if (!fs::is_regular_file(file)) throw InputError(file, "is missing: not a synth-bin folder (or pass --pattern-only)");
  }
  if (!fs::is_regular_file(files.left_passive)) files.left_passive.clear();
  return files;
}

}  // namespace

int run_eval_pick_command(std::vector<std::string> args) {
  if (auto code = usage_exit_code(args, print_help)) return *code;
  PickOptions options = take_pick_options(args);
  PickSettings& settings = options.settings;
  const std::string out = take_option(args, "--out");
  const bool overwrite = take_flag(args, "--overwrite");
  const bool passive_stereo = !take_flag(args, "--pattern-only");
  const std::string limit_text = take_option(args, "--limit");
  std::string models_info = take_option(args, "--models-info");
  reject_unknown_options(args);
  if (args.size() != 1) throw InputError("eval-pick", "expected one BINS_DIR, got " + std::to_string(args.size()));
  if (out.empty()) throw InputError("option --out", "missing: the report folder");
  const fs::path bins_dir = args[0];
  if (!fs::is_directory(bins_dir)) throw InputError(bins_dir.string(), "is not a folder");
  if (models_info.empty()) models_info = default_models_info_beside(settings.cad);

  // The bins: BINS_DIR's subfolders that hold a scene_gt.json, by name.
  std::vector<fs::path> bin_dirs;
  for (const auto& entry : fs::directory_iterator(bins_dir)) {
    if (entry.is_directory() && fs::is_regular_file(entry.path() / "scene_gt.json")) bin_dirs.push_back(entry.path());
  }
  std::sort(bin_dirs.begin(), bin_dirs.end());
  if (!limit_text.empty()) {
    const auto limit = static_cast<std::size_t>(parse_whole_number("--limit", limit_text, 1, 1000000));
    if (bin_dirs.size() > limit) bin_dirs.resize(limit);
  }
  if (bin_dirs.empty()) throw InputError(bins_dir.string(), "holds no bin (no subfolder with a scene_gt.json)");

  // Every input checked before the work: each bin's files and calibration, the models
  // for the scoring, the detector, templates and CAD folder, the output folder.
  std::vector<BinFiles> bins;
  std::vector<std::string> bin_paths;
  for (const fs::path& dir : bin_dirs) {
    bins.push_back(bin_files(dir, passive_stereo));
    pick_ndisp(options, bins.back().calib);
    read_stereo_camera(bins.back().calib);
    bin_paths.push_back(dir.string());
  }
  std::set<int> obj_ids = bin_obj_ids(bin_paths);
  std::map<int, std::string> source_of;
  for (int id : obj_ids) source_of[id] = bins_dir.string();
  PickPipeline pipeline(settings);
  PickReport report;
  report.bins_dir = bins_dir.string();
  report.model = settings.model;
  report.templates = settings.templates;
  report.cad = settings.cad;
  const SsdDetector& detector = pipeline.detector();
  for (const DetectorLabel& label : detector.labels()) {
    report.categories.push_back({label.category_id, label.name});
    if (!source_of.count(label.category_id)) source_of[label.category_id] = settings.model;
    obj_ids.insert(label.category_id);
  }
  const PoseScoringModels models = load_pose_scoring_models(obj_ids, settings.cad, models_info, source_of);
  StagedFolder staged(out, overwrite, "--out");

  for (std::size_t i = 0; i < bins.size(); ++i) {
    const BinFiles& files = bins[i];
    const std::string name = bin_dirs[i].filename().string();
    std::cerr << "eval-pick: bin " << (i + 1) << " of " << bins.size() << " (" << name << ")\n";
    const StereoPair pair = load_stereo_pair(files.left, files.right);
    const StereoCamera rig = read_stereo_camera(files.calib).resized_to(pair.left.cols, pair.left.rows);
    settings.stereo.ndisp = pick_ndisp(options, files.calib);
    pipeline.set_ndisp(settings.stereo.ndisp);
    validate_inputs(pair.left, pair.right, settings.stereo);
    const cv::Mat texture = files.left_passive.empty() ? cv::Mat() : load_rgb8(files.left_passive);
    const PickResult result = pipeline.run(pair.left, pair.right, rig, texture);
    if (report.stereo_path.empty()) report.stereo_path = result.stereo_path;
    cv::Mat no_pattern;
    if (passive_stereo) {
      if (!settings.quiet) std::cerr << "  stereo without the pattern\n";
      const StereoPair passive_pair = load_stereo_pair(files.left_passive, files.right_passive);
      no_pattern = pipeline.disparity(passive_pair.left, passive_pair.right);
    }
    report.bins.push_back(
        score_pick_on_bin(files.dir, result, no_pattern, models, settings.cad, models_info));
    const BinPickScore& score = report.bins.back();
    std::cerr << "  " << score.posed_visib50 << " of " << score.targets_visib50 << " parts >= 50 % visible posed; top pick "
              << (score.top1_correct ? "right" : "wrong") << "; " << seconds_text(score.seconds.total()) << "\n";
    const fs::path staging(staged.path());
    dataset_files::write_text((staging / (name + ".json")).string(),
                              pick_json(result, {files.left, files.right, files.calib, settings.model,
                                                 settings.templates, settings.cad, files.left_passive}));
    cv::Mat picture;
    cv::cvtColor(pick_picture(texture.empty() ? pair.left : texture, result, pipeline.models()), picture,
                 cv::COLOR_BGR2RGB);
    write_image((staging / (name + ".png")).string(), picture);
  }
  summarize(report);
  const fs::path dir(staged.path());
  dataset_files::write_text((dir / "report.json").string(), to_json(report));
  dataset_files::write_text((dir / "report.md").string(), to_markdown(report));
  staged.commit();
  std::cout << to_markdown(report);
  return 0;
}

}  // namespace flexsight
