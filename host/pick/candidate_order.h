#pragma once
// The order pick poses its candidates in, from cues that cost nothing next to a pose
// (docs/pick.md, "The first pick first"). A candidate is a group of overlapping proposal
// boxes (one part proposed as several classes); its cues come from the measured depth in
// and around its box and from the detector's (and namer's) scores. The parts on top of
// the pile, free around them and seen whole, come first: they are the ones most likely
// to be posed right and taken without disturbing others.
#include <opencv2/core.hpp>
#include <vector>

namespace flexsight {

struct CandidateCues {
  // Of the part's top above the bin floor, mm: the floor depth minus a near (10th)
  // percentile of the measured depth in the central half of the box. 0 without depth.
  double height_mm = 0.0;
  // Of the measured pixels in a ring around the box (a quarter of the box's size wide),
  // the share not nearer to the camera than the part's top (within a tolerance): a box
  // whose surroundings are higher is likely covered. 1 when nothing is measured there.
  double free_space = 1.0;
  // Of the measured pixels in the box, the share not nearer than the box centre's median
  // depth (within a tolerance): what of the box is not hidden under a nearer surface.
  double visible_estimate = 0.0;
  double detection_score = 0.0;  // the best of the group's proposals
  double naming_score = -1.0;    // the best of the group's; -1 without a namer
};

// How the cues add up to the cheap score (each cue lies in 0..1; the height is divided
// by the highest candidate's of the bin). Chosen on the development bins (docs/pick.md,
// "The first pick first"): the height counts half, since boxes on the bin's rim are the
// highest of all; the namer's weight was not measured.
struct CandidateOrderWeights {
  double height = 0.5;
  double free_space = 1.0;
  double visible = 1.0;
  double detection = 1.0;
  double naming = 0.5;  // only with a namer
};

struct OrderedCandidate {
  std::vector<int> proposals;  // indices into the proposal list, in proposal order
  cv::Rect box;                // the group's first (lead) proposal's box
  CandidateCues cues;
  double cheap_score = 0.0;
};

// The proposals' boxes grouped: each box joins the first group whose lead box it
// overlaps by IoU above `iou`, else leads a new one. Groups in order of their leads.
std::vector<std::vector<int>> group_overlapping_boxes(const std::vector<cv::Rect>& boxes, double iou);

// The depth cues of `box` (`depth_mm`: CV_32FC1, 0 or NaN where unknown; `floor_depth_mm`:
// floor_depth_mm() of it, 0 when unknown). Scores are left at their defaults.
CandidateCues depth_cues(const cv::Mat& depth_mm, const cv::Rect& box, double floor_depth_mm);

// Sets each candidate's cheap_score and sorts them best first (ties: the earlier lead
// proposal first, so the order is a function of the input alone).
void order_candidates(std::vector<OrderedCandidate>& candidates, const CandidateOrderWeights& weights = {});

}  // namespace flexsight
