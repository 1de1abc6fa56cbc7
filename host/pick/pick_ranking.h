#pragma once
// Which part the robot should take first. Each posed part gets its visible fraction
// (how much of it the camera sees, from the depth: a part under others is a poor first
// pick) and its height in the bin; the ranking puts well-posed, uncovered parts first,
// the higher before the lower when they tie.
#include <memory>
#include <opencv2/core.hpp>
#include <vector>

#include "host/detect/ssd_detector.h"

#include "host/pose/pose_estimator.h"
#include "host/render/mesh.h"
#include "host/render/raycaster.h"

namespace flexsight {

struct PickCandidate {
  int obj_id = 0;
  Pose pose;                     // model -> camera, mm
  cv::Rect box;                  // the detection's box, pixels
  double detection_score = 0.0;  // the detector's
  double naming_score = -1.0;    // the namer's probability of obj_id at the box; -1 without a namer
  double pose_score = 0.0;       // the pose estimator's (edge fit x depth fit), 0..1
  double depth_fit = 0.0;        // the estimator's: of the part's pixels with a measured
                                 // depth, the share that agree with the pose
  double visible_fraction = 0.0; // of the part's pixels at its pose, those not behind
                                 // a nearer measured surface
  double height_mm = 0.0;        // of the part's origin above the bin floor (the
                                 // deepest surface in view), along the optical axis
  double pick_score = 0.0;       // pose_score x visible_fraction: the ranking key
  bool from_depth = false;       // the box is a depth region's (depth_proposals.h)
  int proposal_index = -1;       // the proposal it was posed from (pick_session's list)
  PoseStageTimes times;
};

// The fraction of `mesh`'s pixels at `pose` whose measured depth (`depth_mm`, CV_32FC1,
// 0 or NaN where unknown) is not nearer than the part by more than `tolerance_mm`:
// pixels without a measurement count as seen. 0 when the part projects to no pixel.
double visible_fraction(const std::shared_ptr<const Mesh>& mesh, const Pose& pose, const PinholeCamera& camera, const cv::Mat& depth_mm,
                        double tolerance_mm);

// The depth of the bin floor as the camera sees it: the 95th percentile of the measured
// depths (the floor fills most of a bin's view; the percentile ignores the far outliers
// of a stereo depth map). 0 when nothing is measured.
double floor_depth_mm(const cv::Mat& depth_mm);

// Sets each candidate's pick_score and sorts best first: pick_score descending, then
// the higher part, then the detection order (stable).
void rank_picks(std::vector<PickCandidate>& candidates);

// The detections worth posing: detections (best first) are grouped by box (IoU above
// `iou` with a group's best box) and each group keeps its `classes_per_box` best-scored
// classes. On bins the right class is often not the detector's first but among its
// first few at that place; posing each of them and keeping the best fit
// (remove_duplicate_picks) classifies by the shape, while the groups bound the cost.
// Returns indices into `detections`, best first.
std::vector<int> pose_proposals(const std::vector<ObjectDetection>& detections, int classes_per_box, double iou);

// Keeps, of ranked candidates whose boxes overlap by IoU above `iou`, the first: one
// part proposed as several classes (or twice) is posed as each, and the best fit
// decides what it is.
void remove_duplicate_picks(std::vector<PickCandidate>& ranked, double iou);

}  // namespace flexsight
