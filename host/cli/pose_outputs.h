#pragma once
// What `flexsight pose DATASET --gt-boxes` writes into its output folder: the BOP
// results file, the report (pose metrics and the time per stage) and a picture.
#include <string>
#include <vector>

#include "host/dataset/bop_pose_results.h"
#include "host/dataset/bop_reader.h"
#include "host/eval/pose_report.h"
#include "host/pose/dataset_posing.h"
#include "host/pose/pose_estimator.h"
#include "host/pose/pose_models.h"

namespace flexsight {

// poses.csv, poses.jpg (the first images, outlines of the truth green and of the
// estimates orange), report.json (the scores of flexsight eval-pose plus the times) and
// report.md.
void write_pose_dataset_outputs(const std::string& folder, const BopReader& reader, std::size_t image_count,
                                const std::vector<PoseEstimateRecord>& records, const PoseRunTiming& timing,
                                const PoseReport& report, const PoseModels& models);

}  // namespace flexsight
