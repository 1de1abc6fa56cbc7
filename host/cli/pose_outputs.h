#pragma once
// What `flexsight pose DATASET --gt-boxes` writes into its output folder: the BOP
// results file, the report (pose metrics and the time per stage) and a picture.
#include <string>
#include <vector>

#include "host/cli/pose_inputs.h"
#include "host/dataset/bop_pose_results.h"
#include "host/dataset/bop_reader.h"
#include "host/pose/pose_estimator.h"

namespace flexsight {

void write_pose_dataset_outputs(const std::string& folder, const std::string& dataset,
                                const BopReader& reader, std::size_t image_count,
                                const std::vector<PoseEstimateRecord>& records,
                                const std::vector<PoseStageTimes>& times, const PoseModels& models,
                                double min_visib);

// Median milliseconds per stage over `times`: edges, search, refine, icp, score, total.
std::vector<std::pair<std::string, double>> median_stage_times(const std::vector<PoseStageTimes>& times);

}  // namespace flexsight
