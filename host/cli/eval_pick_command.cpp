// flexsight eval-pick: `pick` on every bin of a `synth bin` folder, scored against the
// bins' ground truth (host/eval/pick_evaluation.h; docs/pick.md).
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <opencv2/imgproc.hpp>

#include "host/cli/arguments.h"
#include "host/cli/commands.h"
#include "host/cli/pick_options.h"
#include "host/dataset/dataset_files.h"
#include "host/eval/pick_box_recall.h"
#include "host/eval/pick_evaluation.h"
#include "host/io/calibration.h"
#include "host/io/image_io.h"
#include "host/io/input_error.h"
#include "host/io/staged_folder.h"
#include "host/pick/pick_outputs.h"
#include "host/sim/bin_folder.h"

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
               "DIR/report.md (pose recall, top-ranked part, the first pick and the seconds to it,\n"
               "detection mAP, stereo bad-2 with and without the pattern, seconds per stage),\n"
               "DIR/BIN.json and DIR/BIN.png per bin (every proposal is posed, in cheap order, as\n"
               "pick --all does; the first pick of pick's default mode is timed on the way);\n"
               "with --depth-proposals on also DIR/box_recall.json (parts >= 50 % visible with a\n"
               "box of any class at IoU 0.5: detector, depth, both) and DIR/BIN_regions.png.\n"
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

void print_bin_score(const BinPickScore& score) {
  std::cerr << "  " << score.posed_visib50 << " of " << score.targets_visib50 << " parts >= 50 % visible posed; top pick "
            << (score.top1_correct ? "right" : "wrong") << "; first pick " << (score.first_pick_correct ? "right" : "wrong")
            << " at " << seconds_text(score.seconds_to_first_pick) << "; " << seconds_text(score.seconds.total()) << "\n";
}

// STAGING/BIN.json and STAGING/BIN.png: `stem` is STAGING/BIN.
void write_bin_outputs(const fs::path& stem, const BinPickRun& run, const BinFiles& files, const PickSettings& settings,
                       const PickSession& session) {
  dataset_files::write_text(stem.string() + ".json",
                            pick_json(run.result, {files.left, files.right, files.calib, settings.model,
                                                   settings.templates, settings.cad, files.left_passive,
                                                   settings.detector.parts.obj_ids}));
  cv::Mat picture;
  cv::cvtColor(pick_picture(run.left_view, run.result, session.models()), picture, cv::COLOR_BGR2RGB);
  write_image(stem.string() + ".png", picture);
  if (run.result.depth_proposals_run) {
    cv::cvtColor(depth_regions_picture(run.left_view, run.result.depth), picture, cv::COLOR_BGR2RGB);
    write_image(stem.string() + "_regions.png", picture);
  }
}

}  // namespace

int run_eval_pick_command(std::vector<std::string> args) {
  if (auto code = usage_exit_code(args, print_help)) return *code;
  PickOptions options = take_pick_options(args);
  PickSettings& settings = options.settings;
  // Every proposal posed (the recall), in cheap order, the first pick timed on the way.
  settings.mode = PickMode::All;
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
  std::vector<fs::path> bin_dirs = list_bin_dirs(bins_dir);
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
    read_stereo_camera(bins.back().calib);  // a bad focal length named as such, not as a missing --ndisp
    StereoParams stereo = settings.stereo;
    stereo.ndisp = pick_ndisp(options, bins.back().calib);
    check_bin_inputs(bins.back(), stereo, passive_stereo);
    bin_paths.push_back(dir.string());
  }
  StagedFolder staged(out, overwrite, "--out");
  PickSession session(settings);
  PickReport report = pick_report_header(bins_dir.string(), settings, session);
  const PoseScoringModels models =
      load_pick_scoring_models(bin_truth_sources(bin_paths), settings, session, models_info);

  std::vector<BoxRecall> box_recalls;  // with --depth-proposals on
  for (std::size_t i = 0; i < bins.size(); ++i) {
    const BinFiles& files = bins[i];
    const std::string name = bin_dirs[i].filename().string();
    std::cerr << "eval-pick: bin " << (i + 1) << " of " << bins.size() << " (" << name << ")\n";
    settings.stereo.ndisp = pick_ndisp(options, files.calib);
    const BinPickRun run = pick_and_score_bin(session, files, settings.stereo, passive_stereo, models, settings, models_info);
    if (report.stereo_path.empty()) report.stereo_path = run.result.stereo_path;
    report.bins.push_back(run.score);
    print_bin_score(run.score);
    if (run.result.depth_proposals_run) box_recalls.push_back(score_box_recall(bin_paths[i], run.result));
    write_bin_outputs(fs::path(staged.path()) / name, run, files, settings, session);
  }
  summarize(report);
  const fs::path dir(staged.path());
  dataset_files::write_text((dir / "report.json").string(), to_json(report));
  dataset_files::write_text((dir / "report.md").string(), to_markdown(report));
  if (!box_recalls.empty()) dataset_files::write_text((dir / "box_recall.json").string(), box_recall_json(box_recalls));
  staged.commit();
  std::cout << to_markdown(report);
  return 0;
}

}  // namespace flexsight
