#pragma once
// The pick job on the bins of a `synth bin` folder, scored against their ground truth
// (`flexsight eval-pick`): the report's header, the models the scoring needs, and one
// bin picked and scored.
#include <opencv2/core.hpp>
#include <map>
#include <set>
#include <string>

#include "host/eval/pick_report.h"
#include "host/pick/pick_session.h"
#include "host/sim/bin_folder.h"

namespace flexsight {

// The report before any bin: its inputs and the detector's classes.
PickReport pick_report_header(const std::string& bins_dir, const PickSettings& settings, const PickSession& session);

// The error models of the bins' ground-truth parts (`truth_sources`: obj_id -> the file
// named in errors) and of every class the detector knows (named after its model).
// Every file of one bin read and checked as the run will use it, before the first bin
// is picked: the calibration (its focal length before the disparity range), both pairs'
// sizes against each other and the calibration, `stereo`'s limits, the one image of
// ground truth, the disparity truth and its mask. InputError naming the file.
void check_bin_inputs(const BinFiles& files, const StereoParams& stereo, bool passive_stereo);

PoseScoringModels load_pick_scoring_models(std::map<int, std::string> truth_sources,
                                           const PickSettings& settings, const PickSession& session,
                                           const std::string& models_info);

struct BinPickRun {
  PickResult result;
  cv::Mat left_view;  // RGB8: the left view without the pattern when the bin has one
  BinPickScore score;
};

// Pick on the bin's pair (`stereo`: the matcher's parameters with the bin's ndisp), the
// matcher alone on its passive pair with `passive_stereo`, and the score.
BinPickRun pick_and_score_bin(PickSession& session, const BinFiles& files, const StereoParams& stereo,
                              bool passive_stereo, const PoseScoringModels& models, const PickSettings& settings,
                              const std::string& models_info);

}  // namespace flexsight
