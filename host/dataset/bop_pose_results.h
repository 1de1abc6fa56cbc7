#pragma once
// Pose estimates in the BOP challenge's results file (the BOP toolkit's
// docs/bop_challenge_2019.md, "Format of results"; inout.save_bop_results and
// load_bop_results): a CSV file with the header
//   scene_id,im_id,obj_id,score,R,t,time
// and one line per estimate, R as 9 space-separated numbers (row-major), t as 3 (mm),
// time the seconds spent on the whole image (-1 when unknown; BOP wants the same time on
// every line of an image). The pose estimator writes it, `flexsight eval-pose` reads it,
// and so can the BOP toolkit.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace flexsight {

struct PoseEstimateRecord {
  int scene_id = 0, im_id = 0, obj_id = 0;
  double score = 0.0;
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();  // x_cam = R x_model + t (mm)
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  double time_s = -1.0;  // BOP: seconds for the image, -1 when unknown
};

// The record of one estimate, its time unknown.
inline PoseEstimateRecord pose_estimate_record(int scene_id, int im_id, int obj_id, double score,
                                               const Eigen::Matrix3d& R, const Eigen::Vector3d& t) {
  PoseEstimateRecord record;
  record.scene_id = scene_id;
  record.im_id = im_id;
  record.obj_id = obj_id;
  record.score = score;
  record.R = R;
  record.t = t;
  return record;
}

// Writes the header and one line per record, in the given order, atomically (a failed
// write leaves any earlier file as it was). Numbers are printed as the shortest text
// that reads back to the same double, so reading the file gives the records back
// exactly. Throws InputError naming `path` when it cannot be written, and for a record
// with a number that is not finite (the file could not be read back).
void write_bop_pose_results(const std::string& path, const std::vector<PoseEstimateRecord>& records);

// Reads a results file, the header line present or absent (BOP's own files have it),
// blank lines and a final line without newline allowed, Windows line ends accepted.
// Throws InputError naming the file and the line number for a line without exactly 7
// comma-separated columns, an id that is not a whole number (or is negative), a number
// that cannot be read or is not finite, R without 9 or t without 3 numbers, and an R
// that is not a rotation or a t beyond 100 m (host/io/physical_checks.h); InputError
// naming the file when it does not exist, cannot be read or is empty (not even a header).
std::vector<PoseEstimateRecord> read_bop_pose_results(const std::string& path);

}  // namespace flexsight
