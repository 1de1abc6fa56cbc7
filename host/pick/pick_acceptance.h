#pragma once
// When pick may answer with a posed part without posing the rest (docs/pick.md, "The
// first pick first"): the pose fits the image and the depth, and nothing measured lies
// over the part. Every figure is one pick already has for each posed part.
#include <string>

#include "host/pick/pick_ranking.h"

namespace flexsight {

struct AcceptanceRule {
  // The pose estimator's score (edge fit x depth fit) at least this: a pose this good is
  // right on the development bins far more often than the detector's first guess.
  double min_pose_score = 0.6;
  // Of the posed part's pixels with a measured depth, the share that agree with it.
  double min_depth_fit = 0.7;
  // Of the part's pixels at its pose, the share not behind a nearer measured surface:
  // a part others lie on is no first pick even when posed right.
  double min_visible_fraction = 0.9;
};

// Empty when `candidate` passes `rule`, else why not (the first figure that fails, with
// its value and the bound), e.g. "pose_score 0.41 < 0.6".
std::string acceptance_failure(const PickCandidate& candidate, const AcceptanceRule& rule);

}  // namespace flexsight
